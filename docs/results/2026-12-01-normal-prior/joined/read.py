"""plan.md's reading against RAD alone at the line's 1 % threshold (from data/line-pv-val, as in the normal-prior
report), which `station compare --split` does not print (it reads each file's own threshold, set on its calibration
set): caught and good parts rejected on seed 1176, per type, and the pair's gain with a paired bootstrap SE.

Usage: python read.py RUNS_DIR (RUNS_DIR: run.sh's runs/c77)"""
import csv
import json
import sys

import numpy as np

runs = sys.argv[1]
split = json.load(open(f"{runs}/split-ING.json"))
chosen = split["splits"][split["chosen"]]
t_rad = split["alone"]["first"]["threshold"]
t1, t2 = chosen["first"], chosen["second"]


def scores(name):
    return {int(r["index"]): (int(r["label"]), r["defect_type"], float(r["score"]))
            for r in csv.DictReader(open(f"{runs}/eval-1176-{name}/scores.csv"))}


a, b = scores("V1"), scores("ING")
idx = sorted(a)
lab = np.array([a[i][0] for i in idx])
typ = np.array([a[i][1] for i in idx])
sa, sb = np.array([a[i][2] for i in idx]), np.array([b[i][2] for i in idx])
rad, pair = sa > t_rad, (sa > t1) | (sb > t2)
print(f"thresholds: RAD alone {t_rad:.4f}; pair {t1:.4f}, {t2:.4f}")
print("| seed 1176 | good parts rejected | caught | " + " | ".join(sorted(set(typ) - {""})) + " |")
for name, r in (("RAD alone, the line's 1 %", rad), ("pair, rule 64's split", pair)):
    g, d = r[lab == 0], r[lab == 1]
    per = [f"{100 * r[typ == t].mean():.0f} %" for t in sorted(set(typ) - {""})]
    print(f"| {name} | {100 * g.mean():.1f} % ({g.sum()} of {g.size}) | {100 * d.mean():.1f} % | " + " | ".join(per)
          + " |")
d = (pair[lab == 1].astype(float) - rad[lab == 1])
rng = np.random.default_rng(0)
boot = [d[rng.integers(0, d.size, d.size)].mean() for _ in range(1000)]
print(f"pair minus RAD alone, defective caught: {100 * d.mean():+.1f} points "
      f"(paired bootstrap SE {100 * np.std(boot):.1f})")
