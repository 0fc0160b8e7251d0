"""Rule 40's criteria from models.sh's outputs: prints markdown tables and the verdict of each criterion.
Usage (repository root): python decide.py"""

from __future__ import annotations

import json
import os

D = "docs/results/2026-11-28-appearance-clusters"
SHIFTS = ("blur 1 px", "dolp x0.5", "dolp x2", "aolp +5 deg", "gamma 1.25", "blur 0.5 px", "rotate 5 deg",
          "zoom x1.05")


def load(path: str) -> dict:
    with open(path) as f:
        return json.load(f)


def caught_1(folder: str) -> float:
    """Caught at 1 % over all defects of a station eval report."""
    return load(f"{folder}/eval.json")["industrial"][0]["caught_at_1%_false_rejects"]


def main() -> None:
    verdicts = []
    print("Seed 1139, unshifted: image AUROC, L against C (paired SE)\n\n"
          "| type | defective | C | L | L - C (SE) | in SEs |\n|---|---|---|---|---|---|")
    all_ok, worst_type = False, 0.0
    for r in load(f"{D}/paired-1139/paired.json")["rows"]:
        n_se = r["gain"] / r["se"] if r["se"] > 0 else 0.0
        print(f"| {r['type']} | {r['defective']} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} "
              f"({r['se']:.3f}) | {n_se:+.1f} |")
        if r["type"] == "all":
            all_ok = r["gain"] >= 2 * r["se"]
        else:
            worst_type = min(worst_type, n_se)
    cc, cl = caught_1(f"{D}/eval-C-1139"), caught_1(f"{D}/eval-L-1139")
    print(f"\nCaught at 1 %: C {100 * cc:.1f} %, L {100 * cl:.1f} %")
    verdicts.append(("(a) all >= +2 SE; no type < -2 SE; caught at 1 % >= C - 2 points",
                     all_ok and worst_type >= -2 and cl >= cc - 0.02))

    sc = {r["shift"]: r for r in load(f"{D}/shift-C/shift.json")["rows"]}
    sl = {r["shift"]: r for r in load(f"{D}/shift-L/shift.json")["rows"]}
    print("\nSeed 1139 under the shifts (`station bench shift`; thresholds from validation)\n\n| shift | AUROC C | "
          "AUROC L | good rejected at 1 %: C | L | at own threshold: C | L |\n|---|---|---|---|---|---|---|")
    for name in sc:
        c, m = sc[name], sl[name]
        print(f"| {name} | {c['image_auroc']:.3f} | {m['image_auroc']:.3f} | {100 * c['good_rejected_1%']:.1f} % | "
              f"{100 * m['good_rejected_1%']:.1f} % | {100 * c['good_rejected_own']:.1f} % | "
              f"{100 * m['good_rejected_own']:.1f} % |")
    verdicts.append(("(b) each shift: good rejected at the own threshold L <= C + 2 points",
                     all(sl[n]["good_rejected_own"] <= sc[n]["good_rejected_own"] + 0.02 for n in SHIFTS)))

    print("\nRules 35-36's re-renders (seed 1133): image AUROC, L against C (paired SE)\n\n"
          "| set | C | L | L - C (SE) |\n|---|---|---|---|")
    ok_c = True
    for s in "GER":
        r = load(f"{D}/paired-{s}/paired.json")["rows"][0]
        print(f"| {s} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} ({r['se']:.3f}) |")
        ok_c &= r["gain"] >= -r["se"]
    verdicts.append(("(c) G, E, R: L - C >= -1 SE", ok_c))

    size = os.path.getsize("runs/r40/L.pt")
    bench = load(f"{D}/bench-L/pipeline.json") if os.path.exists(f"{D}/bench-L/pipeline.json") else None
    p99 = next(r["p99_ms"] for r in bench["rows"] if r["checkpoint"] == "runs/r40/L") if bench else float("nan")
    print(f"\nModel file {size:,} bytes; `station bench pipeline` p99 {p99:.1f} ms")
    verdicts.append(("(d) file <= 30,000,000 bytes and p99 <= 100 ms", size <= 30_000_000 and p99 <= 100))
    print("\n| criterion | holds |\n|---|---|")
    for name, ok in verdicts:
        print(f"| {name} | {'yes' if ok else 'no'} |")


if __name__ == "__main__":
    main()
