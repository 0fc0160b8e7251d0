"""Rule 5 (rule.md): each part's residual maps minus their own Gaussian blur inside the judged part (a normalised
convolution: the blur of the maps over the blur of the judged mask), so a smooth change over a face is taken out
and a local one is kept.

Usage: highpass.py OUT.json [NAME=CACHE ...], from the repository root, after the residual-network study's cache.py;
each NAME=CACHE a held-out cache (its held_* arrays) scored with validation thresholds."""

from __future__ import annotations

import json
import sys

import cv2
import numpy as np
from statistic import run

SIGMAS = (4.0, 8.0)


def highpass(sigma: float):
    def transform(z: np.ndarray, judged: np.ndarray, self_index: np.ndarray | None) -> np.ndarray:
        out = np.empty_like(z)
        for i, (zi, ji) in enumerate(zip(z, judged, strict=True)):
            w = cv2.GaussianBlur(ji.astype(np.float32), (0, 0), sigma)
            for ch, zc in enumerate(zi):
                smooth = cv2.GaussianBlur(zc * ji, (0, 0), sigma) / np.maximum(w, 1e-3)
                out[i, ch] = (zc - smooth) * ji
        return out

    return transform


held = [tuple(a.split("=", 1)) for a in sys.argv[2:]]
json.dump(
    run({"shipped": None, **{f"sigma{s:g}": highpass(s) for s in SIGMAS}}, held), open(sys.argv[1], "w"), indent=1
)
