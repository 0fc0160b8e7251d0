"""Screen: propose-and-test. The shipped map proposes the part's K highest places; at each, the region around it
(the map above FRAC of its peak, connected, at most MAXPX px, grown 1 px) is tested as the localised oracle tests a
defect's pixels: the mean chi-square over the channels there against the calibration half's good parts there.
2-fold on validation as lines.py."""
import sys

import cv2
import numpy as np
from lines import folds, lab, region, report, robust, scores, stat

d = np.load(sys.argv[1])
signed = d["signed"].astype(np.float32)  # (N, C, H, W)
judged = d["judged"]
chi2 = (signed ** 2).sum(1) * judged  # (N, H, W)
box = stat("box5")
K, FRAC, MAXPX = int(sys.argv[2]), float(sys.argv[3]), 400


def calibrated_maps(w: np.ndarray, cal: np.ndarray) -> np.ndarray:
    loc = np.median(w[cal], 0)
    spread = cv2.GaussianBlur(np.percentile(w[cal], 95, 0) - loc, (0, 0), 2.0)
    spread = np.maximum(spread, max(float(np.percentile(spread[region], 5.0)), 0.6028 / 5))
    return np.maximum((w - loc) / spread, 0) * (region & judged)


def proposals(m: np.ndarray) -> list[np.ndarray]:
    out, m = [], m.copy()
    for _ in range(K):
        peak = m.max()
        if peak <= 0:
            break
        y, x = np.unravel_index(m.argmax(), m.shape)
        _, comp = cv2.connectedComponents((m >= FRAC * peak).astype(np.uint8), connectivity=8)
        reg = comp == comp[y, x]
        if reg.sum() > MAXPX:  # keep the MAXPX pixels nearest the peak
            yy, xx = np.nonzero(reg)
            keep = np.argsort((yy - y) ** 2 + (xx - x) ** 2)[:MAXPX]
            reg = np.zeros_like(reg)
            reg[yy[keep], xx[keep]] = True
        reg = cv2.dilate(reg.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
        out.append(reg)
        m[cv2.dilate(reg.astype(np.uint8), np.ones((5, 5), np.uint8)).astype(bool)] = 0
    return out


def test_scores() -> np.ndarray:
    out = np.zeros(len(lab))
    for k in range(2):
        cal = folds[k]
        rest = np.setdiff1d(np.arange(len(lab)), cal)
        maps = calibrated_maps(box, cal)
        for i in rest:
            best = 0.0
            for reg in proposals(maps[i]):
                ref = (chi2[cal][:, reg].sum(1) / np.maximum(judged[cal][:, reg].sum(1), 1))
                own = chi2[i][reg].sum() / max(judged[i][reg].sum(), 1)
                med, q = np.median(ref), np.percentile(ref, 95)
                best = max(best, (own - med) / max(q - med, 1e-6))
            if k == 0 or lab[i] == 0:
                out[i] = best
            else:
                out[i] = (out[i] + best) / 2
    return out


base = scores(box)
report("box5", base)
s = test_scores()
report(f"propose K={K} frac={FRAC}", s)
report("max(box5, propose)", np.maximum(robust(base), robust(s)))
