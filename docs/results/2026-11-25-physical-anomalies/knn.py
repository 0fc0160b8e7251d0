"""Rule 4 (rule.md): a nearest-neighbour correction of the variation model's residuals, on cached maps: each part's
maps minus the mean of its k most similar good training parts' (L2 over the part at 1/4 detail, clipped at +-5 so a
highlight's huge values do not pick the neighbours; never itself).

Usage: knn.py OUT.json [--held212], from the repository root, after the residual-network study's cache.py
(runs/s33/zcache.npz, zcache212.npz)."""

from __future__ import annotations

import json
import sys

import cv2
import numpy as np
from statistic import run, train

KS = (5, 10, 20, 40)


def descriptor(z: np.ndarray) -> np.ndarray:
    h, w = z.shape[2:]
    small = [cv2.resize(np.clip(zc, -5, 5), (w // 4, h // 4), interpolation=cv2.INTER_AREA) for zi in z for zc in zi]
    return np.stack(small).reshape(len(z), -1)


d_train = descriptor(train)


def knn(k: int):
    def transform(z: np.ndarray, judged: np.ndarray, self_index: np.ndarray | None) -> np.ndarray:
        d = descriptor(z)
        dist = (d**2).sum(1)[:, None] - 2 * d @ d_train.T + (d_train**2).sum(1)[None]
        if self_index is not None:
            dist[np.arange(len(z)), self_index] = np.inf
        idx = np.argsort(dist, 1)[:, :k]
        return z - np.stack([train[i].mean(0) for i in idx])

    return transform


held = [("held", "runs/s33/zcache.npz")] + ([("held212", "runs/s33/zcache212.npz")] if "--held212" in sys.argv else [])
json.dump(run({"shipped": None, **{f"k{k}": knn(k) for k in KS}}, held), open(sys.argv[1], "w"), indent=1)
