"""Screen on validation (2-fold: per-place calibration on half the good parts, scored on the other half and every
defect): the shipped 5 x 5 box of the max-channel z against oriented line windows (lineLxW: L x W px, 8 angles) or
boxes over the root chi-square over the channels (chiboxB), alone and the larger.
Usage: python lines.py CACHE.npz chibox5 line9x1 ... (CACHE from lines_cache.py)"""
import sys

import cv2
import numpy as np
from common import report as common_report

d = np.load(sys.argv[1])
z, judged, lab, types, region = d["z"], d["judged"], d["label"], d["types"], d["region"]
good = np.flatnonzero(lab == 0)
rng = np.random.default_rng(0)
folds = np.array_split(rng.permutation(good), 2)


def line_kernel(length: int, width: int, angle: float) -> np.ndarray:
    k = np.zeros((length + 2, length + 2), np.float32)
    c = (length + 1) / 2
    dx, dy = np.cos(angle), np.sin(angle)
    cv2.line(k, (round(c - dx * (length - 1) / 2), round(c - dy * (length - 1) / 2)),
             (round(c + dx * (length - 1) / 2), round(c + dy * (length - 1) / 2)), 1.0, width)
    return k / k.sum()


def stat(kind: str) -> np.ndarray:
    if kind.startswith("box"):  # box5: the shipped window; chibox5: the same over the root chi-square
        return np.stack([cv2.blur(m, (5, 5), borderType=cv2.BORDER_REPLICATE) for m in z])
    if kind.startswith("chibox"):
        b = int(kind[6:])
        return np.stack([cv2.blur(m, (b, b), borderType=cv2.BORDER_REPLICATE) for m in d["chi"]])
    length, width = map(int, kind[4:].split("x"))
    ks = [line_kernel(length, width, a) for a in np.arange(8) * np.pi / 8]
    return np.stack([np.max([cv2.filter2D(m, -1, k, borderType=cv2.BORDER_REPLICATE) for k in ks], 0) for m in z])


def scores(w: np.ndarray) -> np.ndarray:
    """Per-place calibrated maxima, each good part scored by the calibration of the fold it is not in."""
    out = np.zeros(len(w))
    for k in range(2):
        cal, rest = folds[k], np.setdiff1d(np.arange(len(w)), folds[k])
        loc = np.median(w[cal], 0)
        spread = cv2.GaussianBlur(np.percentile(w[cal], 95, 0) - loc, (0, 0), 2.0)
        spread = np.maximum(spread, max(float(np.percentile(spread[region], 5.0)), 0.6028 / 5))
        m = np.maximum((w[rest] - loc) / spread, 0) * (region & judged[rest])
        s = m.reshape(len(rest), -1).max(1)
        if k == 0:
            out[rest] = s
        else:  # defects: the mean of both folds' scores; good parts of fold 0 get fold 1's calibration
            bad = lab[rest] == 1
            out[rest[~bad]] = s[~bad]
            out[rest[bad]] = (out[rest[bad]] + s[bad]) / 2
    return out


def robust(s: np.ndarray) -> np.ndarray:
    g = s[lab == 0]
    med = np.median(g)
    return (s - med) / (1.4826 * np.median(np.abs(g - med)) + 1e-9)


def report(name: str, s: np.ndarray) -> None:
    """``common.report`` on this cache's labels and types, printed."""
    print(common_report(name, s, lab, types), flush=True)


if __name__ == "__main__":
    base = scores(stat("box5"))
    report("box5 (as shipped)", base)
    for kind in sys.argv[2:]:
        s = scores(stat(kind))
        report(kind, s)
        report(f"max(box5, {kind})", np.maximum(robust(base), robust(s)))
