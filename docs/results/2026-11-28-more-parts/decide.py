"""Rule 44's criteria from models.sh's outputs: prints markdown tables and the verdict of each criterion.
Usage (repository root): python decide.py"""

from __future__ import annotations

import json
import os

D = "docs/results/2026-11-28-more-parts"
SHIFTS = ("gamma 1.25", "dolp x0.5", "blur 1 px", "rotate 5 deg", "zoom x1.05")


def load(path: str) -> dict:
    with open(path) as f:
        return json.load(f)


def caught_1(folder: str) -> float:
    """Caught at 1 % over all defects of a station eval report."""
    return load(f"{folder}/eval.json")["industrial"][0]["caught_at_1%_false_rejects"]


def main() -> None:
    verdicts = []
    print("Seed 1144, unshifted: image AUROC, X against C (paired SE)\n\n"
          "| type | defective | C | X | X - C (SE) | in SEs |\n|---|---|---|---|---|---|")
    all_ok, worst_type = False, 0.0
    for r in load(f"{D}/paired-1144/paired.json")["rows"]:
        n_se = r["gain"] / r["se"] if r["se"] > 0 else 0.0
        print(f"| {r['type']} | {r['defective']} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} "
              f"({r['se']:.3f}) | {n_se:+.1f} |")
        if r["type"] == "all":
            all_ok = r["gain"] >= 0
        else:
            worst_type = min(worst_type, n_se)
    cc, cx = caught_1(f"{D}/eval-C-1144"), caught_1(f"{D}/eval-X-1144")
    print(f"\nCaught at 1 %: C {100 * cc:.1f} %, X {100 * cx:.1f} %")
    verdicts.append(("(a) all: X - C >= 0; no type < -2 SE; caught at 1 % >= C - 2 points",
                     all_ok and worst_type >= -2 and cx >= cc - 0.02))

    sc = {r["shift"]: r for r in load(f"{D}/shift-C/shift.json")["rows"]}
    sx = {r["shift"]: r for r in load(f"{D}/shift-X/shift.json")["rows"]}
    print("\nSeed 1144 under the shifts (`station bench shift`; thresholds from validation)\n\n| shift | AUROC C | "
          "AUROC X | good rejected at 1 %: C | X | at own threshold: C | X |\n|---|---|---|---|---|---|---|")
    for name in sc:
        c, m = sc[name], sx[name]
        print(f"| {name} | {c['image_auroc']:.3f} | {m['image_auroc']:.3f} | {100 * c['good_rejected_1%']:.1f} % | "
              f"{100 * m['good_rejected_1%']:.1f} % | {100 * c['good_rejected_own']:.1f} % | "
              f"{100 * m['good_rejected_own']:.1f} % |")
    def rise(rows: dict, name: str) -> float:
        """Good parts rejected at the own threshold under a shift, less the model's unshifted share."""
        return rows[name]["good_rejected_own"] - rows["none"]["good_rejected_own"]

    verdicts.append(("(b) each shift: X's rise over its unshifted share <= C's rise + 2 points",
                     all(rise(sx, n) <= rise(sc, n) + 0.02 for n in SHIFTS)))

    print("\nRules 35-36's re-renders (seed 1133): image AUROC, X against C (paired SE)\n\n"
          "| set | C | X | X - C (SE) |\n|---|---|---|---|")
    ok_c = True
    for s in "GER":
        r = load(f"{D}/paired-{s}/paired.json")["rows"][0]
        print(f"| {s} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} ({r['se']:.3f}) |")
        ok_c &= r["gain"] >= -r["se"]
    verdicts.append(("(c) G, E, R: X - C >= -1 SE", ok_c))

    size = os.path.getsize("runs/r44/X.pt")
    bench = load(f"{D}/bench-X/pipeline.json") if os.path.exists(f"{D}/bench-X/pipeline.json") else None
    rows = {r["checkpoint"]: r for r in bench["rows"]} if bench else {}
    p99 = rows["runs/r44/X"]["p99_ms"] if rows else float("nan")
    if rows:
        c, x = rows["model/weights/default"], rows["runs/r44/X"]
        print(f"\n`station bench pipeline` (one run): p50 C {c['p50_ms']:.1f} ms, X {x['p50_ms']:.1f} ms (ratio "
              f"{x['p50_ms'] / c['p50_ms']:.2f}); p99 C {c['p99_ms']:.1f} ms, X {x['p99_ms']:.1f} ms")
    print(f"\nModel file {size:,} bytes")
    verdicts.append(("(d) file <= 30,000,000 bytes and p99 <= 100 ms", size <= 30_000_000 and p99 <= 100))

    print("\n| criterion | holds |\n|---|---|")
    for name, ok in verdicts:
        print(f"| {name} | {'yes' if ok else 'no'} |")


if __name__ == "__main__":
    main()
