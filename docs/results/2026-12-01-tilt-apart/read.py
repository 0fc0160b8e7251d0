"""Joins read against RAD alone at the line's 1 % threshold (from data/line-pv-val, as `station split` sets it),
which `station compare --split` does not print (it reads each file's own threshold): caught and good parts rejected
on seed 1176, per type, for RAD alone and for each pair at its split, and each pair's gain with a paired bootstrap
SE. A frame a file would not judge (its presence check: `eval.json`'s `unjudged`) is rejected, as the station
rejects it and as `station compare` counts it. Used by this folder's run.sh, 2026-12-01-normal-precision/run.sh
and 2026-12-01-normal-prior/joined/run.sh.

Usage: python read.py RAD_EVAL NAME=EVAL_DIR:SPLIT_JSON ...
(RAD_EVAL: RAD's `station eval` folder on seed 1176; each pair: the second file's eval folder on seed 1176's twin or
copy, and the `station split` of RAD with it)"""
import csv
import json
import sys

import numpy as np


def scores(path):
    """Indices, labels, types and scores; a frame the file would not judge scores +inf (rejected at any threshold)."""
    rows = {int(r["index"]): (int(r["label"]), r["defect_type"], float(r["score"]))
            for r in csv.DictReader(open(f"{path}/scores.csv"))}
    unjudged = {int(i) for i in json.load(open(f"{path}/eval.json")).get("unjudged", {})}
    idx = sorted(rows)
    return idx, np.array([rows[i][0] for i in idx]), np.array([rows[i][1] for i in idx]), \
        np.array([np.inf if i in unjudged else rows[i][2] for i in idx])


def split(path):
    s = json.load(open(path))
    chosen = s["splits"][s["chosen"]]
    return s["alone"]["first"]["threshold"], chosen["first"], chosen["second"]


idx, lab, typ, rad = scores(sys.argv[1])
kinds = sorted(set(typ) - {""})
rows, t_rad = [], None
for arg in sys.argv[2:]:
    name, paths = arg.split("=", 1)
    path, sp = paths.split(":")
    idx2, lab2, _, s2 = scores(path)
    assert idx2 == idx and (lab2 == lab).all(), f"{path} does not hold the parts of {sys.argv[1]}"
    alone, t1, t2 = split(sp)
    assert t_rad is None or abs(alone - t_rad) < 1e-9, f"{sp}: RAD alone's threshold differs"
    t_rad = alone
    rows.append((f"RAD + {name} ({t1:.4f}, {t2:.4f})", (rad > t1) | (s2 > t2)))
rows.insert(0, (f"RAD alone, the line's 1 % ({t_rad:.4f})", rad > t_rad))
print("| seed 1176 (thresholds) | good parts rejected | caught | " + " | ".join(kinds) + " |")
print("|---" * (3 + len(kinds)) + "|")
for name, r in rows:
    g, d = r[lab == 0], r[lab == 1]
    per = [f"{100 * r[typ == t].mean():.0f} %" for t in kinds]
    print(f"| {name} | {100 * g.mean():.1f} % ({g.sum()} of {g.size}) | {100 * d.mean():.1f} % | " + " | ".join(per)
          + " |")
rng = np.random.default_rng(0)
for name, r in rows[1:]:
    d = r[lab == 1].astype(float) - rows[0][1][lab == 1]
    boot = [d[rng.integers(0, d.size, d.size)].mean() for _ in range(1000)]
    print(f"{name.split(' (')[0]} minus RAD alone, defective caught: {100 * d.mean():+.1f} points "
          f"(paired bootstrap SE {100 * np.std(boot):.1f})")
