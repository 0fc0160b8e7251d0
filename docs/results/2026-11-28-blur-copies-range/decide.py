"""Rule 39's criteria from models.sh's outputs: prints markdown tables and the verdict of each criterion.
Usage (repository root): python decide.py"""

from __future__ import annotations

import json

D = "docs/results/2026-11-28-blur-copies-range"
OTHERS = ("dolp x0.5", "dolp x2", "aolp +5 deg", "gamma 1.25", "blur 0.5 px", "rotate 5 deg", "zoom x1.05")


def load(path: str) -> dict:
    with open(path) as f:
        return json.load(f)


def caught_1(folder: str) -> float:
    """Caught at 1 % over all defects of a station eval report."""
    return load(f"{folder}/eval.json")["industrial"][0]["caught_at_1%_false_rejects"]


def main() -> None:
    verdicts = []
    print("Seed 1138, unshifted: image AUROC, D against C (paired SE)\n\n"
          "| type | defective | C | D | D - C (SE) | in SEs |\n|---|---|---|---|---|---|")
    all_ok, worst_type = False, 0.0
    for r in load(f"{D}/paired-1138/paired.json")["rows"]:
        n_se = r["gain"] / r["se"] if r["se"] > 0 else 0.0
        print(f"| {r['type']} | {r['defective']} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} "
              f"({r['se']:.3f}) | {n_se:+.1f} |")
        if r["type"] == "all":
            all_ok = r["gain"] >= -r["se"]
        else:
            worst_type = min(worst_type, n_se)
    cc, cd = caught_1(f"{D}/eval-C-1138"), caught_1(f"{D}/eval-D-1138")
    print(f"\nCaught at 1 %: C {100 * cc:.1f} %, D {100 * cd:.1f} %")
    verdicts.append(("(a) all > -1 SE; no type < -2 SE; caught at 1 % >= C - 2 points",
                     all_ok and worst_type > -2 and cd >= cc - 0.02))

    sc = {r["shift"]: r for r in load(f"{D}/shift-C/shift.json")["rows"]}
    sd = {r["shift"]: r for r in load(f"{D}/shift-D/shift.json")["rows"]}
    print("\nSeed 1138 under the shifts (`station bench shift`; thresholds from validation)\n\n| shift | AUROC C | "
          "AUROC D | good rejected at 1 %: C | D | at own threshold: C | D |\n|---|---|---|---|---|---|---|")
    for name in sc:
        c, d = sc[name], sd[name]
        print(f"| {name} | {c['image_auroc']:.3f} | {d['image_auroc']:.3f} | {100 * c['good_rejected_1%']:.1f} % | "
              f"{100 * d['good_rejected_1%']:.1f} % | {100 * c['good_rejected_own']:.1f} % | "
              f"{100 * d['good_rejected_own']:.1f} % |")
    c, d = sc["blur 1 px"], sd["blur 1 px"]
    verdicts.append(("(b) blur 1 px: AUROC D >= C + 0.01; good rejected at the own threshold <= max(C / 2, 5 %)",
                     d["image_auroc"] >= c["image_auroc"] + 0.01
                     and d["good_rejected_own"] <= max(c["good_rejected_own"] / 2, 0.05)))
    verdicts.append(("(c) each other shift: good rejected at the own threshold D <= C + 2 points",
                     all(sd[n]["good_rejected_own"] <= sc[n]["good_rejected_own"] + 0.02 for n in OTHERS)))

    print("\nRules 35-36's re-renders (seed 1133): image AUROC, D against C (paired SE)\n\n"
          "| set | C | D | D - C (SE) |\n|---|---|---|---|")
    ok_d = True
    for s in "GER":
        r = load(f"{D}/paired-{s}/paired.json")["rows"][0]
        print(f"| {s} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} ({r['se']:.3f}) |")
        ok_d &= r["gain"] >= -r["se"]
    verdicts.append(("(d) G, E, R: D - C >= -1 SE", ok_d))
    print("\n| criterion | holds |\n|---|---|")
    for name, ok in verdicts:
        print(f"| {name} | {'yes' if ok else 'no'} |")


if __name__ == "__main__":
    main()
