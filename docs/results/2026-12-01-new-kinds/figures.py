"""report.md's figure: the new kinds on seed 1179 as the camera shows them (intensity S0 and DoLP of the renderer's
Stokes around the defect, its mask outlined), caught and missed by the shipped file at its threshold.

Usage: python figures.py DATA EVAL_DIR OUT.png"""
import csv
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

THRESHOLD = 0.9785  # the shipped file's 1 % threshold on data/line-pv-val (eval.md)


def main() -> None:
    data, folder, out = Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3]
    rows = list(csv.DictReader(open(folder / "scores.csv")))
    picks = []
    for kind in ("blister", "debris"):
        ms = sorted((r for r in rows if r["defect_type"] == kind), key=lambda r: -float(r["score"]))
        caught = [r for r in ms if float(r["score"]) > THRESHOLD]
        missed = [r for r in ms if float(r["score"]) <= THRESHOLD]
        picks += [(kind, "caught", caught[len(caught) // 2]), (kind, "missed", missed[len(missed) // 4]),
                  (kind, "missed", missed[len(missed) // 2])]
    fig, ax = plt.subplots(2, len(picks), figsize=(2.6 * len(picks), 5.6))
    for k, (kind, fate, r) in enumerate(picks):
        d = data / "samples" / f"{int(r['index']):06d}"
        p = json.loads((d / "params.json").read_text())["defect"]
        g = np.load(d / "gt.npz")
        m = g["defect_mask"]
        ys, xs = np.nonzero(m)
        cy, cx = int(ys.mean()), int(xs.mean())
        sl = (slice(max(cy - 32, 0), cy + 32), slice(max(cx - 32, 0), cx + 32))
        s0 = g["s0"][sl]
        dolp = np.hypot(g["s1"], g["s2"])[sl] / np.maximum(s0, 1e-6)
        size = (f"h {p['height_mm']:.2f} r {p['radius_mm']:.1f} mm" if kind == "blister"
                else f"r {p['radius_mm']:.2f} mm grey {p['grey']:.2f}")
        ax[0, k].imshow(s0, cmap="gray")
        ax[0, k].set_title(f"{kind}, {fate}\n{size}\nscore {float(r['score']):.2f}, {p['visible_px']} px", fontsize=8)
        ax[1, k].imshow(dolp, cmap="magma", vmin=0, vmax=0.6)
        for a in ax[:, k]:
            a.contour(m[sl], levels=[0.5], colors="c", linewidths=0.6)
            a.set_xticks([])
            a.set_yticks([])
    ax[0, 0].set_ylabel("intensity S0")
    ax[1, 0].set_ylabel("DoLP")
    fig.tight_layout()
    fig.savefig(out, dpi=90)


if __name__ == "__main__":
    main()
