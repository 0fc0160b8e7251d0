"""The moulding kinds' figure (plan.md): each defect's line-camera score against the size that governs its
visibility (station eval's by-size measure), the file's threshold drawn; good parts' scores beside. Scores are drawn
as -log10(1 - score), which spreads the top of the squashed scale where the threshold lies. Run from the
repository's root after run.sh: python docs/results/2026-12-05-moulding-kinds/figures.py"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from sim.defects import defect_size

HERE = Path(__file__).parent
DATA = Path("data/moulding-1198/samples")
KINDS = ("sink", "short_shot", "warp")


def lift(score: float) -> float:
    return float(-np.log10(max(1.0 - score, 1e-6)))


def main() -> None:
    rows = list(csv.DictReader(open(HERE / "eval/line/scores.csv")))
    threshold = json.loads((HERE / "eval/line/eval.json").read_text())["threshold"]
    samples = sorted(DATA.iterdir())
    fig, axes = plt.subplots(1, 4, figsize=(15, 3.6), gridspec_kw={"width_ratios": [1, 3, 3, 3]})
    good = [lift(float(r["score"])) for r in rows if r["label"] == "0"]
    axes[0].plot([0] * len(good), good, "k.", alpha=0.3)
    axes[0].set(title=f"good ({len(good)})", xticks=[], ylabel="line camera's score, -log10(1 - score)")
    for ax, kind in zip(axes[1:], KINDS, strict=True):
        xs, ys = [], []
        for r in rows:
            if r["defect_type"] != kind:
                continue
            defect = json.loads((samples[int(r["index"])] / "params.json").read_text())["defect"]
            assert defect["type"] == kind
            name, size = defect_size(defect)
            xs.append(size)
            ys.append(lift(float(r["score"])))
        caught = sum(y > lift(threshold) for y in ys)
        ax.plot(xs, ys, "r.", alpha=0.7)
        ax.set(title=f"{kind}: {caught} of {len(ys)} caught", xlabel=name)
    for ax in axes:
        ax.axhline(lift(threshold), color="b", lw=0.8)
        ax.set_ylim(0, 3.5)
    fig.tight_layout()
    fig.savefig(HERE.parent / "2026-12-05-moulding-kinds.png", dpi=90)


if __name__ == "__main__":
    main()
