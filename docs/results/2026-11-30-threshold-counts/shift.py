"""Each camera's good scores on validation (seed 303, runs/s72/val-*.csv from valscores.py) against seed 1173's
(check 71's station eval reports), at the split's thresholds. Writes to stdout (shift.txt)."""
import csv

import numpy as np
from scipy.stats import mannwhitneyu

from model.draem.rate_bounds import interval

thr = {"line": 0.97996, "side": 0.985522}
for cam, ho in (("line", "runs/c71/eval-line-1173/scores.csv"), ("side", "runs/c71/eval-side-1173/scores.csv")):
    v = np.array([float(r["score"]) for r in csv.DictReader(open(f"runs/s72/val-{cam}.csv")) if r["label"] == "0"])
    h = np.array([float(r["score"]) for r in csv.DictReader(open(ho)) if r["label"] == "0"])
    t = thr[cam]
    kv, kh = int((v > t).sum()), int((h > t).sum())
    print(cam, f"val good {len(v)}, above {kv} ({100*kv/len(v):.1f} %); 1173 good {len(h)}, above {kh} "
          f"({100*kh/len(h):.1f} %, CI {[round(100*x,1) for x in interval(kh, len(h))]})")
    for q in (50, 90, 95, 99):
        print(f"  q{q}: val {np.percentile(v, q):.4f}  1173 {np.percentile(h, q):.4f}")
    print("  MWU p (1173 > val):", mannwhitneyu(h, v, alternative="greater").pvalue)
    for thx in (0.5, 0.8, 0.9, 0.95):
        print(f"  share above {thx}: val {100*(v>thx).mean():.1f} %  1173 {100*(h>thx).mean():.1f} %")
