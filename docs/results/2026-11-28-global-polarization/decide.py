"""Rule 37's criteria from models.sh's outputs: prints markdown tables and the verdict of each criterion.
Usage (repository root): python decide.py"""

from __future__ import annotations

import json

D = "docs/results/2026-11-28-global-polarization"


def load(path: str) -> dict:
    return json.load(open(path))


def caught_1(folder: str) -> tuple[float, float]:
    """(caught at 1 %, image AUROC) over all defects of a station eval report."""
    row = load(f"{folder}/eval.json")["industrial"][0]
    return row["caught_at_1%_false_rejects"], row["image_auroc"]


def main() -> None:
    verdicts = []
    rows = load(f"{D}/paired-1134/paired.json")["rows"]
    print("Seed 1134, unshifted: image AUROC, B against A (paired SE)\n\n"
          "| type | defective | A | B | B - A (SE) | in SEs |\n|---|---|---|---|---|---|")
    worst_type = 0.0
    for r in rows:
        n_se = r["gain"] / r["se"] if r["se"] > 0 else 0.0
        print(f"| {r['type']} | {r['defective']} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} "
              f"({r['se']:.3f}) | {n_se:+.1f} |")
        if r["type"] == "all":
            all_ok = n_se > -1
        else:
            worst_type = min(worst_type, n_se)
    (ca, _), (cb, _) = caught_1(f"{D}/eval-A-1134"), caught_1(f"{D}/eval-B-1134")
    print(f"\nCaught at 1 %: A {100 * ca:.1f} %, B {100 * cb:.1f} %")
    verdicts.append(("(a) all > -1 SE; no type < -2 SE; caught at 1 % >= A - 2 points",
                     all_ok and worst_type > -2 and cb >= ca - 0.02))

    sa = {r["shift"]: r for r in load(f"{D}/shift-A/shift.json")["rows"]}
    sb = {r["shift"]: r for r in load(f"{D}/shift-B/shift.json")["rows"]}
    print("\nSeed 1134 under the shifts (`station bench shift`; thresholds from validation)\n\n| shift | AUROC A | "
          "AUROC B | good rejected at 1 %: A | B | at own threshold: A | B |\n|---|---|---|---|---|---|---|")
    ok_b = True
    for name in sa:
        a, b = sa[name], sb[name]
        print(f"| {name} | {a['image_auroc']:.3f} | {b['image_auroc']:.3f} | {100 * a['good_rejected_1%']:.1f} % | "
              f"{100 * b['good_rejected_1%']:.1f} % | {100 * a['good_rejected_own']:.1f} % | "
              f"{100 * b['good_rejected_own']:.1f} % |")
        if name != "none":
            ok_b &= (b["image_auroc"] >= a["image_auroc"] + 0.02
                     and b["good_rejected_1%"] <= a["good_rejected_1%"] + 0.01)
    verdicts.append(("(b) each shift: AUROC B >= A + 0.02, good rejected at 1 % B <= A + 1 point", ok_b))

    print("\nRules 35-36's sets (seed 1133): image AUROC, B against A (paired SE)\n\n| set | A | B | B - A (SE) |"
          "\n|---|---|---|---|")
    ok_c = True
    for s in "SGER":
        r = load(f"{D}/paired-{s}/paired.json")["rows"][0]
        print(f"| {s} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} ({r['se']:.3f}) |")
        if s != "S":
            ok_c &= r["gain"] > -r["se"]
    verdicts.append(("(c) G, E, R: B - A > -1 SE", ok_c))
    print("\n| criterion | holds |\n|---|---|")
    for name, ok in verdicts:
        print(f"| {name} | {'yes' if ok else 'no'} |")


if __name__ == "__main__":
    main()
