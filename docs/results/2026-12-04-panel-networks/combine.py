"""Screen: the shipped decision (E63's score) and the panel line's band network, each as a robust z on the good
parts of the same validation set (median, 1.4826 MAD, as the variation model's combined rule), the larger decides.
Caught at k good parts rejected (in-sample: thresholds on the same parts), per type, and AUROC.

    python combine.py E63-FOLDER BAND-FOLDER    (each holding a station eval's scores.csv of the same parts)
"""
import csv
import sys

import numpy as np

from model.draem.metrics import rank_auroc


def read(folder):
    rows = sorted(csv.DictReader(open(f"{folder}/scores.csv")), key=lambda r: int(r["index"]))
    return (np.array([int(r["label"]) for r in rows]), np.array([r["defect_type"] for r in rows]),
            np.array([float(r["score"]) for r in rows]))


def z(s, y):
    g = s[y == 0]
    med = np.median(g)
    return (s - med) / max(1.4826 * np.median(np.abs(g - med)), 1e-6)


def caught(y, s, k):
    g = np.sort(s[y == 0])[::-1]
    return (s[y == 1] > g[k]).mean(), g[k]


y, kind, e = read(sys.argv[1])
y2, _, n = read(sys.argv[2])
assert (y == y2).all()
c = np.maximum(z(e, y), z(n, y))
for name, s in (("E63", e), ("band net", n), ("combined", c)):
    parts = [f"AUROC {rank_auroc(y, s):.3f}"]
    for k in (1, 3, 5, 18):
        parts.append(f"k={k}: {100 * caught(y, s, k)[0]:.1f}")
    t = caught(y, s, 3)[1]
    per = " ".join(f"{ty}:{100 * (s[kind == ty] > t).mean():.0f}" for ty in sorted(set(kind[y == 1])))
    print(f"{name:9s} {', '.join(parts)} | at k=3 {per}")
print(f"{(y == 0).sum()} good, {(y == 1).sum()} defective")
