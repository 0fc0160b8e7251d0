"""Rule 21 (rule.md): a ridge statistic on the variation model's cached signed residual maps, beside the shipped
window statistic, on one labelled set of the cache, with paired bootstrap SEs.

Usage: ridge.py CACHE OUT.json [TAG]  (CACHE from docs/results/2026-11-25-residual-networks/cache.py; TAG the set
it scores, ``val`` (default) or ``held``; the per-place calibration comes from the cache's training parts)."""

from __future__ import annotations

import json
import sys

import cv2
import numpy as np

sys.path.insert(0, "docs/results/2026-11-25-physical-anomalies")
from bootstrap import compare

from model.draem.variation import ABS_NORMAL_SD, MEDIAN_ABS_NORMAL, NOISE_CAP, WINDOW_BLUR_PX, WINDOW_QUANTILE

BOX = 5
VARIANTS = {"9x1": (9, 1, 3), "15x1": (15, 1, 3), "15x3": (15, 3, 4)}  # core length, core width, flank offset (px)
ANGLES = 8


def level(z: np.ndarray, judged: np.ndarray) -> float:
    s = float(np.median(np.abs(z[:, judged]))) / MEDIAN_ABS_NORMAL if judged.any() else 1.0
    return s if 1.0 < s <= NOISE_CAP else 1.0


def kernels(length: int, width: int, offset: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """(core, flanks) binary float32 kernels for each orientation: the core |u| <= L/2, |v| <= W/2 along the line u,
    the flanks the same length at |v| within W/2 of the offset, on both sides."""
    r = int(np.ceil(max(length / 2, offset + width / 2))) + 1
    y, x = np.mgrid[-r: r + 1, -r: r + 1].astype(np.float32)
    out = []
    for k in range(ANGLES):
        t = np.pi * k / ANGLES
        u, v = x * np.cos(t) + y * np.sin(t), -x * np.sin(t) + y * np.cos(t)
        along = np.abs(u) <= length / 2
        core = along & (np.abs(v) <= width / 2)
        flank = along & (np.abs(np.abs(v) - offset) <= max(width, 1) / 2)
        out.append((core.astype(np.float32), flank.astype(np.float32)))
    return out


def ridge(z: np.ndarray, judged: np.ndarray, ks: list[tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
    """(C, H, W) signed z (after the noise level) and (H, W) judged -> (H, W) the largest over orientations of the
    root chi-square over channels of (core mean - flank mean), masked averages over judged pixels; 0 where either
    covers under 60 % judged pixels."""
    jf = judged.astype(np.float32)
    zj = z * jf
    best = np.zeros(judged.shape, np.float32)
    for kc, kf in ks:
        nc = cv2.filter2D(jf, -1, kc, borderType=cv2.BORDER_CONSTANT)
        nf = cv2.filter2D(jf, -1, kf, borderType=cv2.BORDER_CONSTANT)
        ok = (nc >= 0.6 * kc.sum()) & (nf >= 0.6 * kf.sum())
        chi = np.zeros_like(best)
        for ch in zj:
            d = (cv2.filter2D(ch, -1, kc, borderType=cv2.BORDER_CONSTANT) / np.maximum(nc, 1e-6)
                 - cv2.filter2D(ch, -1, kf, borderType=cv2.BORDER_CONSTANT) / np.maximum(nf, 1e-6))
            chi += d * d
        best = np.maximum(best, np.sqrt(chi) * ok)
    return best


def window(z: np.ndarray, judged: np.ndarray) -> np.ndarray:
    """The shipped window statistic (5 x 5 box of the largest channel's |z|), before its per-place calibration."""
    return cv2.blur(np.abs(z).max(0), (BOX, BOX), borderType=cv2.BORDER_REPLICATE)


def maps(zs: np.ndarray, judged: np.ndarray, stat) -> np.ndarray:
    out = []
    for z, j in zip(zs, judged, strict=True):
        z = z.astype(np.float32)
        z = z / level(z, j) * j
        out.append(stat(z, j))
    return np.stack(out)


def calibrate(train_maps: np.ndarray, region: np.ndarray, floor: float) -> tuple[np.ndarray, np.ndarray]:
    loc = np.median(train_maps, 0)
    spread = cv2.GaussianBlur(np.percentile(train_maps, WINDOW_QUANTILE, 0) - loc, (0, 0), WINDOW_BLUR_PX)
    return loc, np.maximum(spread, max(float(np.percentile(spread[region], 5.0)), floor))


def scores(m: np.ndarray, judged: np.ndarray, cal, eroded: np.ndarray) -> np.ndarray:
    loc, spread = cal
    s = np.maximum((m - loc) / spread, 0.0) * (judged & eroded)
    return s.reshape(len(s), -1).max(1)


def robust(s: np.ndarray, ref: np.ndarray) -> np.ndarray:
    med = np.median(ref)
    return (s - med) / (1.4826 * np.median(np.abs(ref - med)) + 1e-9)


def main() -> None:
    c = np.load(sys.argv[1])
    region = c["region"]
    eroded = cv2.erode(region.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
    train = c["train_z"]
    tj = np.repeat(region[None], len(train), 0)
    tag = sys.argv[3] if len(sys.argv) > 3 else "val"
    sets = {tag: tuple(c[f"{tag}_{k}"] for k in ("z", "judged", "label", "type", "score"))}
    stats = {"shipped": (window, ABS_NORMAL_SD / BOX)}
    for name, (ln, w, off) in VARIANTS.items():
        ks = kernels(ln, w, off)
        stats[name] = (lambda z, j, ks=ks: ridge(z, j, ks), 0.05)
    cands: dict[str, dict[str, np.ndarray]] = {k: {} for k in sets}
    train_scores = {}
    for name, (stat, floor) in stats.items():
        tm = maps(train, tj, stat)
        cal = calibrate(tm, region, floor)
        train_scores[name] = scores(tm, tj, cal, eroded)
        for k, (z, j, *_rest) in sets.items():
            cands[k][name] = scores(maps(z, j, stat), j, cal, eroded)
        print(name, "done", flush=True)
    for k in sets:
        base = robust(cands[k]["shipped"], train_scores["shipped"])
        for name in VARIANTS:
            cands[k][f"max-{name}"] = np.maximum(base, robust(cands[k][name], train_scores[name]))
    z, j, lab, typ, shipped_score = sets[tag]
    print("correlation with the model's own scores:", np.corrcoef(cands[tag]["shipped"], shipped_score)[0, 1])
    result = {tag: compare(lab, typ, cands[tag])}
    json.dump(result, open(sys.argv[2], "w"), indent=1, default=lambda o: bool(o) if isinstance(o, np.bool_) else o)


if __name__ == "__main__":
    main()
