"""The page's two figures (validation set only).

    python figures.py dents data/line-pv-val dents.png     # top-face dents: the renderer's Stokes and the raw frame's
    python figures.py zmaps data/line-pv-val zmaps.png 000457 000084 000542 000367 000396 000073
"""
import json
import os
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from PIL import Image

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import aolp_screen as a

from model.priors.demosaic import mosaic_to_stokes
from model.priors.mosaic import normalize_mosaic


def dolp_aolp(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return np.hypot(s1, s2) / np.maximum(s0, 1e-6), np.degrees(0.5 * np.arctan2(s2, s1))


def dents(root: str, out: str) -> None:
    """Six top-face dents spread over their steepest tilt: S0, DoLP, AoLP (+-15 deg) rendered and from the frame."""
    found = []
    for name in sorted(os.listdir(f"{root}/samples")):
        d = json.load(open(f"{root}/samples/{name}/params.json")).get("defect") or {}
        if d.get("type") == "dent" and d["normal"][2] > 0.9:
            found.append((name, np.degrees(np.arctan(np.pi / 2 * d["depth_mm"] / d["radius_mm"])), d["visible_px"]))
    found = sorted(found, key=lambda r: r[1])[:: max(1, len(found) // 6)][:6]
    fig, ax = plt.subplots(len(found), 6, figsize=(14, 2.4 * len(found)))
    for i, (name, tilt, px) in enumerate(found):
        g = np.load(f"{root}/samples/{name}/gt.npz")
        raw = np.array(Image.open(f"{root}/samples/{name}/raw.png"))
        ys, xs = np.nonzero(g["defect_mask"])
        cy, cx = int(ys.mean()), int(xs.mean())
        crop = (slice(max(cy - 30, 0), cy + 30), slice(max(cx - 30, 0), cx + 30))
        rendered = (g["s0"], g["s1"], g["s2"])
        framed = mosaic_to_stokes(normalize_mosaic(raw, 12).data)
        maps = [(rendered[0], "rendered S0"), (dolp_aolp(*rendered)[0], "rendered DoLP"),
                (dolp_aolp(*rendered)[1], "rendered AoLP"), (framed[0], "frame S0"),
                (dolp_aolp(*framed)[0], "frame DoLP"), (dolp_aolp(*framed)[1], "frame AoLP")]
        for j, (im, title) in enumerate(maps):
            c, axis = im[crop], ax[i, j]
            if "AoLP" in title:
                axis.imshow(c, cmap="coolwarm", vmin=-15, vmax=15)
            else:
                axis.imshow(c, cmap="gray")
            axis.contour(g["defect_mask"][crop], [0.5], colors="lime", linewidths=0.5)
            axis.set_title(title, fontsize=7)
            axis.axis("off")
        ax[i, 0].text(0, -12, f"{name}: tilt {tilt:.1f} deg, {px} px", fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=80)


def zmaps(root: str, out: str, names: list[str]) -> None:
    """Per part: the frame's S0 in the band, the pixels judged, the z map at sigma 5 (+-8)."""
    fig, ax = plt.subplots(len(names), 3, figsize=(15, 2.6 * len(names)))
    for i, n in enumerate(names):
        sample = f"{root}/samples/{n}"
        s = a.stokes_of(sample)
        _, mask = a.im_map(*s, a.top_prior())
        score, z = a.zmaps(sample)[5.0]
        defect = np.load(f"{sample}/gt.npz")["defect_mask"][a.BAND]
        ax[i, 0].imshow(s[0], cmap="gray")
        ax[i, 1].imshow(mask, cmap="gray")
        ax[i, 2].imshow(z, cmap="coolwarm", vmin=-8, vmax=8)
        for axis in ax[i]:
            if defect.any():
                axis.contour(defect, [0.5], colors="lime", linewidths=0.6)
            axis.axis("off")
        ax[i, 0].set_title(f"{n} score {score:.1f}", fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=70)


if __name__ == "__main__":
    if sys.argv[1] == "dents":
        dents(sys.argv[2], sys.argv[3])
    else:
        zmaps(sys.argv[2], sys.argv[3], sys.argv[4:])
