"""Check 66's figure: front-face defects of seed 1167 from each camera, the frame's intensity and DoLP (demosaiced
from the raw mosaic, as the station computes them; DoLP smoothed by a Gaussian of ``SMOOTH_PX``, about the model's
input pixel, since a frame pixel's DoLP is mostly noise) around the defect, its mask outlined.

Usage (repository root): python docs/results/2026-11-30-front-view/figure66.py OUT.png INDEX [INDEX ...]
"""

from __future__ import annotations

import sys

import cv2
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from model.priors.api import compute_priors
from sim.dataset import Dataset, Sample

SETS = {"line camera": "data/line-panel-heldout-1167", "second camera": "data/fv-heldout-1167"}
SMOOTH_PX = 2.5
"""Gaussian sigma, frame px, of the DoLP shown: the model reads the frame at 0.4x."""
HALF = 60
"""Half the side of the crop around the defect's centre, frame px."""


def frame_maps(sample: Sample, bit_depth: int) -> tuple[np.ndarray, np.ndarray]:
    """A loaded sample's frame: its intensity and DoLP as the station demosaics them (full-scale units, DoLP in
    [0, 1]), the DoLP smoothed by ``SMOOTH_PX``. ``bit_depth``: the set's (its manifest's)."""
    p = compute_priors(sample.raw, bit_depth=bit_depth, priors=("intensity", "dolp"))
    return p["intensity"], cv2.GaussianBlur(p["dolp"], (0, 0), SMOOTH_PX)


def crop(a: np.ndarray, cy: int, cx: int) -> np.ndarray:
    return a[max(cy - HALF, 0):cy + HALF, max(cx - HALF, 0):cx + HALF]


def show(a, img: np.ndarray, mask: np.ndarray, title: str, **kw) -> None:
    """Axis ``a``: ``img`` cropped around the centre of the defect ``mask`` (the frame's centre when it is empty),
    the mask outlined, titled ``title``; ``kw`` go to ``imshow``."""
    ys, xs = np.nonzero(mask)
    cy, cx = (int(ys.mean()), int(xs.mean())) if ys.size else (mask.shape[0] // 2, mask.shape[1] // 2)
    a.imshow(crop(img, cy, cx), **kw)
    if ys.size:
        a.contour(crop(mask, cy, cx), [0.5], colors="r", linewidths=0.6)
    a.set_title(title, fontsize=8)
    a.axis("off")


def main() -> None:
    out, parts = sys.argv[1], [int(i) for i in sys.argv[2:]]
    sets = {name: Dataset(root) for name, root in SETS.items()}
    fig, ax = plt.subplots(len(parts), 4, figsize=(10, 2.6 * len(parts)), squeeze=False)
    for r, i in enumerate(parts):
        for c, (name, ds) in enumerate(sets.items()):
            sample = ds.load(i)
            intensity, dolp = frame_maps(sample, ds.manifest["bit_depth"])
            defect = sample.params["defect"] or {}
            for k, (img, kw, what) in enumerate(((intensity, {"cmap": "gray", "vmin": 0, "vmax": 1}, "intensity"),
                                                 (dolp, {"cmap": "viridis", "vmin": 0, "vmax": 0.12}, "DoLP"))):
                show(ax[r, 2 * c + k], img, sample.defect_mask > 0, f"{i} {defect.get('type', '')}: {name}, {what}",
                     **kw)
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main()
