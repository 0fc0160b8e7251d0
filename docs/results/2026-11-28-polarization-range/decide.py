"""Rule 38's criteria from models.sh's outputs: prints markdown tables and the verdict of each criterion.
Usage (repository root): python decide.py"""

from __future__ import annotations

import json

D = "docs/results/2026-11-28-polarization-range"
SHIFTS = ("dolp x0.5", "dolp x2", "aolp +5 deg")


def load(path: str) -> dict:
    with open(path) as f:
        return json.load(f)


def caught_1(folder: str) -> float:
    """Caught at 1 % over all defects of a station eval report."""
    return load(f"{folder}/eval.json")["industrial"][0]["caught_at_1%_false_rejects"]


def main() -> None:
    verdicts = []
    print("Seed 1136, unshifted: image AUROC, C against A (paired SE)\n\n"
          "| type | defective | A | C | C - A (SE) | in SEs |\n|---|---|---|---|---|---|")
    all_ok, worst_type = False, 0.0
    for r in load(f"{D}/paired-1136/paired.json")["rows"]:
        n_se = r["gain"] / r["se"] if r["se"] > 0 else 0.0
        print(f"| {r['type']} | {r['defective']} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} "
              f"({r['se']:.3f}) | {n_se:+.1f} |")
        if r["type"] == "all":
            all_ok = r["gain"] >= -r["se"]  # (equal parts give gain 0 and SE 0)
        else:
            worst_type = min(worst_type, n_se)
    ca, cc = caught_1(f"{D}/eval-A-1136"), caught_1(f"{D}/eval-C-1136")
    print(f"\nCaught at 1 %: A {100 * ca:.1f} %, C {100 * cc:.1f} %")
    verdicts.append(("(a) all > -1 SE; no type < -2 SE; caught at 1 % >= A - 2 points",
                     all_ok and worst_type > -2 and cc >= ca - 0.02))

    sa = {r["shift"]: r for r in load(f"{D}/shift-A/shift.json")["rows"]}
    sc = {r["shift"]: r for r in load(f"{D}/shift-C/shift.json")["rows"]}
    print("\nSeed 1136 under the shifts (`station bench shift`; thresholds from validation)\n\n| shift | AUROC A | "
          "AUROC C | good rejected at 1 %: A | C | at own threshold: A | C |\n|---|---|---|---|---|---|---|")
    ok_b = True
    for name in sa:
        a, c = sa[name], sc[name]
        print(f"| {name} | {a['image_auroc']:.3f} | {c['image_auroc']:.3f} | {100 * a['good_rejected_1%']:.1f} % | "
              f"{100 * c['good_rejected_1%']:.1f} % | {100 * a['good_rejected_own']:.1f} % | "
              f"{100 * c['good_rejected_own']:.1f} % |")
        if name in SHIFTS:
            ok_b &= (c["image_auroc"] >= a["image_auroc"] + 0.01
                     and c["good_rejected_own"] <= max(a["good_rejected_own"] / 2, 0.05))
    verdicts.append(("(b) each shift: AUROC C >= A + 0.01; good rejected at the own threshold <= max(A / 2, 5 %)",
                     ok_b))

    print("\nRules 35-36's re-renders (seed 1133): image AUROC, C against A (paired SE)\n\n"
          "| set | A | C | C - A (SE) |\n|---|---|---|---|")
    ok_c = True
    for s in "GER":
        r = load(f"{D}/paired-{s}/paired.json")["rows"][0]
        print(f"| {s} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} ({r['se']:.3f}) |")
        ok_c &= r["gain"] >= -r["se"]
    verdicts.append(("(c) G, E, R: C - A > -1 SE", ok_c))
    print("\n| criterion | holds |\n|---|---|")
    for name, ok in verdicts:
        print(f"| {name} | {'yes' if ok else 'no'} |")


if __name__ == "__main__":
    main()
