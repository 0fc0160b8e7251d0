"""The good parts' spread in the two fits of rule 31 (read after its outcome, to understand it): the variation
model's per-pixel scale (robust spread of good parts' residuals, feature units: log intensity, S1/S0, S2/S0) in
bands of the reference frame, and a figure of the mean log intensity and its scale under each line.
Usage: python scales.py runs/fl/P runs/fl/Q OUT.png (prints a markdown table)."""

from __future__ import annotations

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from model.draem.checkpoint import load_checkpoint

BANDS = {"top face (rows 30-54)": (30, 55), "front face, middle (rows 62-77)": (62, 78),
         "front face, bottom (rows 79-85)": (79, 86)}
"""Rows of the 96 x 192 reference frame (columns 25-124: the brick, not the plug)."""


def main() -> None:
    paths, out = sys.argv[1:3], sys.argv[3]
    print("| line | band | log I | S1/S0 | S2/S0 |\n|---|---|---|---|---|")
    fig, ax = plt.subplots(2, 2, figsize=(10, 4.5))
    for j, path in enumerate(paths):
        v = load_checkpoint(path).detector.variation
        scale = (v.scale * v.channel_scale[:, None, None]).numpy()
        region = v.region.numpy()
        for name, (r0, r1) in BANDS.items():
            m = np.zeros_like(region)
            m[r0:r1, 25:125] = True
            m &= region
            print(f"| {path} | {name} | " + " | ".join(f"{np.median(scale[c][m]):.3f}" for c in (0, 2, 3)) + " |")
        ax[0, j].imshow(np.where(region, v.mean[0].numpy(), np.nan))
        ax[0, j].set_title(f"{path}: mean log intensity", fontsize=8)
        ax[1, j].imshow(np.where(region, scale[0], np.nan), vmin=0, vmax=0.15)
        ax[1, j].set_title("good parts' spread in log intensity (0 to 0.15)", fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=70)


if __name__ == "__main__":
    main()
