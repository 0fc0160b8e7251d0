"""Rule 6 (rule.md): a local appearance model on the variation model's residuals: over a grid of 16 x 16 px patches
(stride 8), each part's patch (three channels together) minus its projection on the first k principal components of
the good training parts' patches there (a training part's own from the folds without it), overlapping patches
averaged.

Usage: localpca.py OUT.json [K,K...] [--held212], from the repository root, after the residual-network study's
cache.py."""

from __future__ import annotations

import json
import sys

import numpy as np
from statistic import region, run, train

from model.draem.variation import FOLDS

PATCH, STRIDE = 16, 8
KS = tuple(int(k) for k in sys.argv[2].split(",")) if len(sys.argv) > 2 and "," in sys.argv[2] else (2, 4, 8)
H, W = region.shape
CORNERS = [
    (y, x)
    for y in range(0, H - PATCH + 1, STRIDE)
    for x in range(0, W - PATCH + 1, STRIDE)
    if region[y : y + PATCH, x : x + PATCH].any()
]
FOLD = np.arange(len(train)) % FOLDS


def patches(z: np.ndarray, y: int, x: int) -> np.ndarray:
    return z[:, :, y : y + PATCH, x : x + PATCH].reshape(len(z), -1)


def basis(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    mean = rows.mean(0)
    return mean, np.linalg.svd(rows - mean, full_matrices=False)[2][: max(KS)]


BASES = {}
for y, x in CORNERS:
    p = patches(train, y, x)
    BASES[(y, x)] = [basis(p)] + [basis(p[FOLD != f]) for f in range(FOLDS)]
print(f"{len(CORNERS)} patches", flush=True)
weight = np.zeros((H, W), np.float32)
for y, x in CORNERS:
    weight[y : y + PATCH, x : x + PATCH] += 1


def local(k: int):
    def transform(z: np.ndarray, judged: np.ndarray, self_index: np.ndarray | None) -> np.ndarray:
        z = z * judged[:, None]
        out = np.zeros_like(z)
        for (y, x), bases in BASES.items():
            p = patches(z, y, x)
            r = np.empty_like(p)
            groups = (
                [(np.ones(len(z), bool), bases[0])]
                if self_index is None
                else [(FOLD[self_index] == f, bases[1 + f]) for f in range(FOLDS)]
            )
            for sel, (mean, comps) in groups:
                q = p[sel] - mean
                r[sel] = q - (q @ comps[:k].T) @ comps[:k]
            out[:, :, y : y + PATCH, x : x + PATCH] += r.reshape(len(z), z.shape[1], PATCH, PATCH)
        return out / np.maximum(weight, 1) * judged[:, None]

    return transform


held = [("held", "runs/s33/zcache.npz")] + ([("held212", "runs/s33/zcache212.npz")] if "--held212" in sys.argv else [])
json.dump(run({"shipped": None, **{f"k{k}": local(k) for k in KS}}, held), open(sys.argv[1], "w"), indent=1)
