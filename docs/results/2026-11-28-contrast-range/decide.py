"""Rule 41's criteria from models.sh's outputs: prints markdown tables and the verdict of each criterion.
Usage (repository root): python decide.py"""

from __future__ import annotations

import json

D = "docs/results/2026-11-28-contrast-range"
OTHERS = ("dolp x0.5", "dolp x2", "aolp +5 deg", "blur 1 px", "blur 0.5 px", "rotate 5 deg", "zoom x1.05")


def load(path: str) -> dict:
    with open(path) as f:
        return json.load(f)


def caught_1(folder: str) -> float:
    """Caught at 1 % over all defects of a station eval report."""
    return load(f"{folder}/eval.json")["industrial"][0]["caught_at_1%_false_rejects"]


def main() -> None:
    verdicts = []
    print("Seed 1140, unshifted: image AUROC, K against C (paired SE)\n\n"
          "| type | defective | C | K | K - C (SE) | in SEs |\n|---|---|---|---|---|---|")
    all_ok, worst_type = False, 0.0
    for r in load(f"{D}/paired-1140/paired.json")["rows"]:
        n_se = r["gain"] / r["se"] if r["se"] > 0 else 0.0
        print(f"| {r['type']} | {r['defective']} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} "
              f"({r['se']:.3f}) | {n_se:+.1f} |")
        if r["type"] == "all":
            all_ok = r["gain"] >= -r["se"]  # identical scores: gain 0, SE 0
        else:
            worst_type = min(worst_type, n_se)
    cc, ck = caught_1(f"{D}/eval-C-1140"), caught_1(f"{D}/eval-K-1140")
    print(f"\nCaught at 1 %: C {100 * cc:.1f} %, K {100 * ck:.1f} %")
    verdicts.append(("(a) all > -1 SE; no type < -2 SE; caught at 1 % >= C - 2 points",
                     all_ok and worst_type >= -2 and ck >= cc - 0.02))

    sc = {r["shift"]: r for r in load(f"{D}/shift-C/shift.json")["rows"]}
    sk = {r["shift"]: r for r in load(f"{D}/shift-K/shift.json")["rows"]}
    print("\nSeed 1140 under the shifts (`station bench shift`; thresholds from validation)\n\n| shift | AUROC C | "
          "AUROC K | good rejected at 1 %: C | K | at own threshold: C | K |\n|---|---|---|---|---|---|---|")
    for name in sc:
        c, m = sc[name], sk[name]
        print(f"| {name} | {c['image_auroc']:.3f} | {m['image_auroc']:.3f} | {100 * c['good_rejected_1%']:.1f} % | "
              f"{100 * m['good_rejected_1%']:.1f} % | {100 * c['good_rejected_own']:.1f} % | "
              f"{100 * m['good_rejected_own']:.1f} % |")
    c, k = sc["gamma 1.25"], sk["gamma 1.25"]
    verdicts.append(("(b) gamma 1.25: good rejected at the own threshold K <= max(C / 2, 10 %); gamma 0.8: K <= C + 2 "
                     "points", k["good_rejected_own"] <= max(c["good_rejected_own"] / 2, 0.10)
                     and sk["gamma 0.8"]["good_rejected_own"] <= sc["gamma 0.8"]["good_rejected_own"] + 0.02))
    verdicts.append(("(c) each other shift: good rejected at the own threshold K <= C + 2 points",
                     all(sk[n]["good_rejected_own"] <= sc[n]["good_rejected_own"] + 0.02 for n in OTHERS)))

    print("\nRules 35-36's re-renders (seed 1133): image AUROC, K against C (paired SE)\n\n"
          "| set | C | K | K - C (SE) |\n|---|---|---|---|")
    ok_c = True
    for s in "GER":
        r = load(f"{D}/paired-{s}/paired.json")["rows"][0]
        print(f"| {s} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} ({r['se']:.3f}) |")
        ok_c &= r["gain"] >= -r["se"]
    verdicts.append(("(d) G, E, R: K - C >= -1 SE", ok_c))

    print("\n| criterion | holds |\n|---|---|")
    for name, ok in verdicts:
        print(f"| {name} | {'yes' if ok else 'no'} |")


if __name__ == "__main__":
    main()
