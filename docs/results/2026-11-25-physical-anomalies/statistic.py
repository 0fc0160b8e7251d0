"""The shipped window statistic recomputed on cached residual maps (runs/s33/zcache.npz, from the residual-network
study's cache.py), with a transform of the residual maps applied first (rules 4 and 5, rule.md). The cache holds each
part's signed residual per channel in units of the model's per-pixel scale, before the frame's noise level (train:
each from the appearance fitted without it). The identity transform gives the shipped statistic (correlation with the
model's own scores printed by the callers)."""

from __future__ import annotations

from collections.abc import Callable

import cv2
import numpy as np

from model.draem.variation import ABS_NORMAL_SD, MEDIAN_ABS_NORMAL, NOISE_CAP, WINDOW_BLUR_PX, WINDOW_QUANTILE

BOX = 5
c = np.load("runs/s33/zcache.npz")
region = c["region"]
eroded = cv2.erode(region.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
train = c["train_z"].astype(np.float32) * region
Transform = Callable[[np.ndarray, np.ndarray, np.ndarray | None], np.ndarray]
"""(N, C, H, W) residual maps, (N, H, W) judged pixels, training indices of the parts or None -> transformed maps."""


def level(z: np.ndarray, judged: np.ndarray) -> float:
    s = float(np.median(np.abs(z[:, judged]))) / MEDIAN_ABS_NORMAL if judged.any() else 1.0
    return s if 1.0 < s <= NOISE_CAP else 1.0


def windows(zs: np.ndarray, judged: np.ndarray) -> np.ndarray:
    return np.stack(
        [
            cv2.blur((np.abs(z) / level(z, j)).max(0), (BOX, BOX), borderType=cv2.BORDER_REPLICATE)
            for z, j in zip(zs, judged, strict=True)
        ]
    )


def fit(transform: Transform | None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per-pixel scale of the transformed training residuals and their window location and spread."""
    judged = np.repeat(region[None], len(train), 0)
    ct = train if transform is None else transform(train, judged, np.arange(len(train)))
    scale = np.ones(ct.shape[1:], np.float32)
    if transform is not None:
        scale = 1.4826 * np.median(np.abs(ct), 0)
        floor = np.array([np.percentile(s[region], 5.0) for s in scale])
        scale = np.maximum(scale, floor[:, None, None])
    w = windows(ct / scale, judged)
    loc = np.median(w, 0)
    spread = cv2.GaussianBlur(np.percentile(w, WINDOW_QUANTILE, 0) - loc, (0, 0), WINDOW_BLUR_PX)
    spread = np.maximum(spread, max(float(np.percentile(spread[region], 5.0)), ABS_NORMAL_SD / BOX))
    return scale, loc, spread


def scores(zs: np.ndarray, judged: np.ndarray, transform: Transform | None, model) -> np.ndarray:
    scale, loc, spread = model
    out = []
    for i in range(0, len(zs), 50):
        z, j = zs[i : i + 50].astype(np.float32) * region, judged[i : i + 50]
        w = windows((z if transform is None else transform(z, j, None)) / scale, j)
        for wi, ji in zip(w, j, strict=True):
            out.append(float(np.maximum((wi - loc) / spread, 0)[eroded & ji].max(initial=0.0)))
    return np.array(out)


def run(transforms: dict[str, Transform | None], held: list[tuple[str, str]]) -> dict:
    """Validation comparison (``bootstrap.compare``) of each transform against the shipped statistic ("shipped":
    None), and each held-out (name, cache path) set with validation thresholds."""
    from bootstrap import compare, held_out

    models = {k: fit(t) for k, t in transforms.items()}
    lv = c["val_label"]
    val = {k: scores(c["val_z"], c["val_judged"], t, models[k]) for k, t in transforms.items()}
    print("shipped against the model's own scores: correlation", np.corrcoef(val["shipped"], c["val_score"])[0, 1])
    result = {"validation": compare(lv, c["val_type"], val)}
    for name, path in held:
        cc = np.load(path)
        hs = {k: scores(cc["held_z"], cc["held_judged"], t, models[k]) for k, t in transforms.items()}
        result[name] = held_out(cc["held_label"], cc["held_type"], hs, lv, val, name)
    return result
