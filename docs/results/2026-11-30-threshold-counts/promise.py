"""The shipped file's threshold by the station's rule and by a promise (choose_threshold(..., confidence=0.95)) on
its validation set (runs/s72/val-line.csv from valscores.py), read on seed 1173 (check 71's station eval scores).
Writes to stdout (promise.txt)."""
import csv

import numpy as np

from model.draem.metrics import choose_threshold
from model.draem.rate_bounds import interval


def read(path):
    rows = list(csv.DictReader(open(path)))
    return np.array([int(r["label"]) for r in rows]), np.array([float(r["score"]) for r in rows])


y, s = read("runs/s72/val-line.csv")
hy, hs = read("runs/c71/eval-line-1173/scores.csv")
for confidence in (None, 0.95):
    c = choose_threshold(y, s, 0.01, confidence)
    k, n = int((hs[hy == 0] > c.threshold).sum()), int((hy == 0).sum())
    lo, hi = interval(k, n)
    print(f"confidence {confidence}: threshold {c.threshold:.5f} ({c.rule}); validation: caught "
          f"{100 * c.detected_fraction:.1f} %; seed 1173: good rejected {k} of {n} ({100 * lo:.1f}-{100 * hi:.1f} %), "
          f"caught {100 * (hs[hy == 1] > c.threshold).mean():.1f} % of {int(hy.sum())}")
