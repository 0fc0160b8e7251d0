"""Paired comparison of two evaluations of the same parts: python paired.py A/scores.csv B/scores.csv [threshold]."""
import csv
import sys

import numpy as np


def read(path):
    return {int(r["index"]): r for r in csv.DictReader(open(path))}


a, b = read(sys.argv[1]), read(sys.argv[2])
t = float(sys.argv[3]) if len(sys.argv) > 3 else 0.9785128235816956
idx = sorted(set(a) & set(b))
la = np.array([int(a[i]["label"]) for i in idx])
lb = np.array([int(b[i]["label"]) for i in idx])
sa = np.array([float(a[i]["score"]) for i in idx])
sb = np.array([float(b[i]["score"]) for i in idx])
print(f"{len(idx)} parts; labels differ on {(la != lb).sum()}")
d = sb - sa
print(f"score B - A: median {np.median(d):+.4f}, 95th pct |d| {np.quantile(abs(d), .95):.4f}, "
      f"max |d| {abs(d).max():.4f}")
same = la == lb
for lab, name in ((0, "good"), (1, "defective")):
    s = same & (la == lab)
    fa, fb = sa[s] > t, sb[s] > t
    print(f"{name}: {s.sum()} parts; above threshold A {fa.sum()}, B {fb.sum()}; "
          f"A only {(fa & ~fb).sum()}, B only {(fb & ~fa).sum()}")
if (la != lb).any():
    for i in np.array(idx)[la != lb]:
        print("  label differs:", i, a[i]["defect_type"], a[i]["label"], b[i]["label"], a[i]["score"], b[i]["score"])
