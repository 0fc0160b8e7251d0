"""After plan-4's reading, not deciding: precision.py's slope error with the prediction fitted on each part alone (the
cubic in the normal times (1, column), 40 coefficients per part) instead of one prediction for all parts. What is
left is the measurement's own scatter at 1 mm on a face that mirrors the light, with what differs from part to part
(its pose, its distance from the camera) taken out, as a variation model's components take out a global turn.

Usage: PYTHONPATH=. python precision-per-part.py F_SET LINE_SET PHASE_PER_SLOPE [PARTS]  (default 20 parts)"""
import sys

import numpy as np
from scipy.ndimage import gaussian_filter

from sim.dataset import open_dataset

A_MIN = 0.08  # as precision.py
f_set, line_set = open_dataset(sys.argv[1]), open_dataset(sys.argv[2])
phase_per_slope = float(sys.argv[3])
want = int(sys.argv[4]) if len(sys.argv) > 4 else 20
errs, shares = [], []
for i in f_set.indices("val") + f_set.indices("train"):
    s = f_set.load(i)
    if s.label:
        continue
    n = line_set.load(i).normal.astype(np.float64)
    mask = s.object_mask
    w = gaussian_filter(mask.astype(np.float64), 10.0)
    sm = [gaussian_filter(s.normal[..., k].astype(np.float64) * mask, 10.0) / np.maximum(w, 1e-9) for k in (0, 1)]
    nsm = np.stack([gaussian_filter(n[..., k] * mask, 10.0) / np.maximum(w, 1e-9) for k in range(3)], -1)
    where = mask & (w > 0.9) & (np.hypot(*sm) > A_MIN)
    z, (x, y, v) = (sm[0] + 1j * sm[1])[where], nsm[where].T
    column = np.broadcast_to(np.linspace(-1, 1, mask.shape[1]), mask.shape)[where]
    cubic = np.stack([x ** a * y ** b * v ** c for a in range(4) for b in range(4 - a) for c in range(4 - a - b)], 1)
    cubic = np.concatenate([cubic, cubic * column[:, None]], 1)
    beta = np.linalg.lstsq(cubic.astype(np.complex128), z / np.abs(z), rcond=None)[0]
    errs.append(np.degrees(np.abs(np.angle(z * np.conj(cubic @ beta)))) / phase_per_slope)
    shares.append(np.median(np.abs(z)))
    if len(errs) == want:
        break
err = np.concatenate(errs)
print(f"{sys.argv[1]}: {len(errs)} good parts, each part's own prediction; slope error along the stripes at 10 px: "
      f"median {np.median(err):.3f} deg, 90th percentile {np.percentile(err, 90):.3f} deg; the stripes' share a: "
      f"median {np.median(shares):.2f}")
