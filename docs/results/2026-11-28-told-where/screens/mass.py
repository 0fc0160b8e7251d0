"""Screen: the mass of the variation map's connected regions above u (the sum of their excess) against its peak,
alone and the larger of the two (each in robust SD over the good parts), on argmax.py's saved maps.
Usage: PYTHONPATH=. python mass.py runs/diag/val-maps.npz"""

import sys

import cv2
import numpy as np
from common import report

d = np.load(sys.argv[1])
maps, lab, types = d["maps"].astype(np.float32), d["label"], d["types"]
good = lab == 0


def mass(m: np.ndarray, u: float) -> float:
    ex = np.maximum(m - u, 0)
    n, comp = cv2.connectedComponents((ex > 0).astype(np.uint8), connectivity=8)
    return float(np.bincount(comp.ravel(), ex.ravel(), minlength=n)[1:].max()) if n > 1 else 0.0


def robust(s: np.ndarray) -> np.ndarray:
    med = np.median(s[good])
    return (s - med) / (1.4826 * np.median(np.abs(s[good] - med)) + 1e-9)


peak = maps.reshape(len(maps), -1).max(1)
print(report("peak (shipped)", peak, lab, types))
for u in (0.5, 1.0, 2.0, 3.0):
    ms = np.array([mass(m, u) for m in maps])
    print(report(f"mass u={u}", ms, lab, types))
    print(report(f"max(peak, mass) u={u}", np.maximum(robust(peak), robust(ms)), lab, types))
