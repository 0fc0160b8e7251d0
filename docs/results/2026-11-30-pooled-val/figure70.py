"""Check 70's figure: good parts rejected against defective parts caught, the line camera alone (shipped threshold)
and the two cameras' split (a_l 0.9785, a_s 0.9895, chosen on validation in checks 69 and 70), on seeds 1171 and
1172, with the line camera's whole curve over its thresholds beside.

Usage (repository root):
    python docs/results/2026-11-30-pooled-val/figure70.py OUT.png LINE_EVAL:SIDE_EVAL:SEED ...
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "2026-11-30-front-view"))
from compare66 import aligned

from station.eval_compare import read_report, read_scores

A_L, A_S = 0.9785, 0.9895


def main() -> None:
    out, runs = sys.argv[1], [a.split(":") for a in sys.argv[2:]]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for (line_eval, side_eval, seed), colour in zip(runs, ("C0", "C1", "C2"), strict=False):
        _, y, _, sl, ss = aligned(read_scores(line_eval), read_scores(side_eval))
        ts = np.unique(np.r_[sl, 0.0, 1.0])
        ax.plot([100 * (sl[~y] > t).mean() for t in ts], [100 * (sl[y] > t).mean() for t in ts], colour,
                lw=1, alpha=0.6, label=f"seed {seed}: line camera alone, every threshold")
        shipped = float(read_report(line_eval)["threshold"])
        line, split = sl > shipped, (sl > A_L) | (ss > A_S)
        ax.plot(100 * line[~y].mean(), 100 * line[y].mean(), "o", color=colour, mfc="none", ms=8,
                label=f"seed {seed}: line camera, shipped threshold")
        ax.plot(100 * split[~y].mean(), 100 * split[y].mean(), "*", color=colour, ms=12,
                label=f"seed {seed}: two cameras, split")
    ax.axvline(1, color="grey", ls=":", lw=1)
    ax.axvline(2, color="grey", ls="--", lw=1)
    ax.set_xlim(0, 8)
    ax.set_ylim(60, 100)
    ax.set_xlabel("good parts rejected (%)")
    ax.set_ylabel("defective parts caught (%)")
    ax.set_title("Checks 69-70: the second camera beside the line camera (held-out renders)", fontsize=9)
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(out, dpi=120)


if __name__ == "__main__":
    main()
