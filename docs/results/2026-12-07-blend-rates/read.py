"""plan.md's read: the shipped file's cascade C against its blend D on one fresh set: at matched rates of good parts
rejected (threshold from the set's good parts; ../2026-12-07-matched-rates/curves.py's rule) with a bootstrap SE of
D - C, and each at its own 1 % threshold from the good validation parts (../2026-12-07-ggx-train/screen.py's
Decisions).

Usage: python read.py SET (SET's test split; run from the repository's root with PYTHONPATH=.)."""

import sys

import numpy as np

sys.path[:0] = ["docs/results/2026-12-07-ggx-train", "docs/results/2026-12-07-matched-rates"]
from curves import RATES, caught_at  # noqa: E402
from screen import Decisions, arrays  # noqa: E402

MODEL = "model/weights/default"


def main(data: str) -> None:
    f = Decisions(MODEL)
    a = arrays(MODEL, f"{data}:test")
    lab = a["label"]
    c, d = f.cascade(a), f.blend(a)
    print(f"== {data}: {int((~lab).sum())} good, {int(lab.sum())} defective parts")
    for name, s in (("C", c), ("D", d)):
        rej = s > f.thresholds[name]
        print(f"{name} at its own threshold {f.thresholds[name]:.4f}: {int(rej[~lab].sum())} of {int((~lab).sum())} "
              f"good rejected ({100 * rej[~lab].mean():.2f} %), {int(rej[lab].sum())} of {int(lab.sum())} defective "
              f"caught ({100 * rej[lab].mean():.1f} %)")
    gi, di = np.flatnonzero(~lab), np.flatnonzero(lab)
    rng = np.random.default_rng(0)
    boots = []
    for _ in range(2000):
        g, k = rng.choice(gi, len(gi)), rng.choice(di, len(di))
        boots.append([caught_at(d[g], d[k], r) - caught_at(c[g], c[k], r) for r in RATES])
    boots = np.array(boots)
    diffs = []
    print("| good parts rejected at most | C caught | D caught | D - C (points) | bootstrap SE |")
    print("|---|---|---|---|---|")
    for j, r in enumerate(RATES):
        cc, cd = caught_at(c[gi], c[di], r), caught_at(d[gi], d[di], r)
        diffs.append(cd - cc)
        print(f"| {100 * r:.0f} % ({int(np.floor(r * len(gi)))} of {len(gi)}) | {100 * cc:.1f} % | {100 * cd:.1f} % | "
              f"{100 * (cd - cc):+.1f} | {100 * boots[:, j].std(ddof=1):.1f} |")
    print(f"mean D - C over the three rates: {100 * np.mean(diffs):+.2f} points (bootstrap SE "
          f"{100 * boots.mean(axis=1).std(ddof=1):.1f})")


if __name__ == "__main__":
    main(sys.argv[1])
