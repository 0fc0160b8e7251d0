"""Check 61 (plan.md): each file on S, G and R at its own threshold, paired over the same parts.
Usage: python decide61.py RUNS_DIR  (reads RUNS_DIR/eval-{K3,C,A}-{S,G,R}/scores.csv and eval.json)."""
import json
import sys
from pathlib import Path

import numpy as np

from model.draem.metrics import auroc
from station.eval_compare import read_scores

runs = Path(sys.argv[1])
rng = np.random.default_rng(0)
BOOT = 1000


def read(name):
    """(labels, decision scores) in dataset order and the file's threshold, or None when not evaluated."""
    d = runs / f"eval-{name}"
    if not (d / "scores.csv").exists():
        return None
    scores = read_scores(d)
    idx = sorted(scores)
    return (np.array([scores[i][0] for i in idx]), np.array([scores[i][2] for i in idx]),
            float(json.loads((d / "eval.json").read_text())["threshold"]))


def figures(y, s, th):
    return auroc(y, s), float((s[y == 0] > th).mean()), float((s[y == 1] > th).mean())


print("| file | set | image AUROC | good parts rejected at its threshold | defective parts caught there |"
      " AUROC change (SE) | good rejected change, points (SE) | holds |")
print("|---|---|---|---|---|---|---|---|")
for f in ("K3", "C", "A"):
    base = read(f"{f}-S")
    if base is None:
        continue
    y, s0, th = base
    a0, g0, c0 = figures(y, s0, th)
    print(f"| {f} | S | {a0:.3f} | {100 * g0:.1f} % | {100 * c0:.1f} % | | | |")
    for k in ("G", "R"):
        other = read(f"{f}-{k}")
        if other is None:
            continue
        y1, s1, _ = other
        assert (y1 == y).all(), "the sets' parts differ"
        a1, g1, c1 = figures(y, s1, th)
        da, dg = [], []
        for _ in range(BOOT):
            b = rng.integers(len(y), size=len(y))
            yb = y[b]
            if yb.min() == yb.max():
                continue
            da.append(auroc(yb, s1[b]) - auroc(yb, s0[b]))
            dg.append((s1[b][yb == 0] > th).mean() - (s0[b][yb == 0] > th).mean())
        holds = (a0 - a1 < 0.03) and (g1 <= 2 * g0 + 0.02)
        print(f"| {f} | {k} | {a1:.3f} | {100 * g1:.1f} % | {100 * c1:.1f} % | {a1 - a0:+.3f} ({np.std(da):.3f}) |"
              f" {100 * (g1 - g0):+.1f} ({100 * np.std(dg):.1f}) | {'yes' if holds else 'NO'} |")
