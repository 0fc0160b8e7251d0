"""Check 66's figure: front-face defects of seed 1167 from each camera, the frame's intensity and DoLP (demosaiced
from the raw mosaic, as the station computes them; DoLP smoothed by a Gaussian of ``SMOOTH_PX``, about the model's
input pixel, since a frame pixel's DoLP is mostly noise) around the defect, its mask outlined.

Usage (repository root): python docs/results/2026-11-30-front-view/figure66.py OUT.png INDEX [INDEX ...]
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import cv2
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from model.priors.api import compute_priors

SETS = {"line camera": "data/line-panel-heldout-1167", "second camera": "data/fv-heldout-1167"}
SMOOTH_PX = 2.5
"""Gaussian sigma, frame px, of the DoLP shown: the model reads the frame at 0.4x."""
HALF = 60
"""Half the side of the crop around the defect's centre, frame px."""


def crop(a: np.ndarray, cy: int, cx: int) -> np.ndarray:
    return a[max(cy - HALF, 0):cy + HALF, max(cx - HALF, 0):cx + HALF]


def main() -> None:
    out, parts = sys.argv[1], [int(i) for i in sys.argv[2:]]
    fig, ax = plt.subplots(len(parts), 4, figsize=(10, 2.6 * len(parts)), squeeze=False)
    for r, i in enumerate(parts):
        for c, (name, data) in enumerate(SETS.items()):
            d = Path(data) / "samples" / f"{i:06d}"
            meta = json.loads((Path(data) / "manifest.json").read_text())
            raw = cv2.imread(str(d / "raw.png"), cv2.IMREAD_UNCHANGED)
            p = compute_priors(raw, bit_depth=meta["bit_depth"], priors=("intensity", "dolp"))
            mask = np.load(d / "gt.npz")["defect_mask"] > 0
            ys, xs = np.nonzero(mask)
            cy, cx = (int(ys.mean()), int(xs.mean())) if ys.size else (raw.shape[0] // 2, raw.shape[1] // 2)
            defect = json.loads((d / "params.json").read_text())["defect"] or {}
            for k, (img, kw, what) in enumerate(((p["intensity"], {"cmap": "gray", "vmin": 0, "vmax": 1}, "intensity"),
                                                 (cv2.GaussianBlur(p["dolp"], (0, 0), SMOOTH_PX),
                                                  {"cmap": "viridis", "vmin": 0, "vmax": 0.12}, "DoLP"))):
                a = ax[r, 2 * c + k]
                a.imshow(crop(img, cy, cx), **kw)
                if ys.size:
                    a.contour(crop(mask, cy, cx), [0.5], colors="r", linewidths=0.6)
                a.set_title(f"{i} {defect.get('type', '')}: {name}, {what}", fontsize=8)
                a.axis("off")
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main()
