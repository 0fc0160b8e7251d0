"""The shipped file (rule 63) and the file before (K3) on seed 1165, each at its own threshold, paired over the parts.
Usage: python report1165.py NEW_EVAL OLD_EVAL (station eval report folders)."""
import json
import sys
from pathlib import Path

import numpy as np

from model.draem.metrics import auroc, paired_auroc_gains
from station.eval_compare import read_scores

rng = np.random.default_rng(0)


def read(d):
    scores = read_scores(d)
    idx = sorted(scores)
    return (np.array([scores[i][0] for i in idx]), np.array([scores[i][1] for i in idx]),
            np.array([scores[i][2] for i in idx]), float(json.loads((Path(d) / "eval.json").read_text())["threshold"]))


y, types, new, tn = read(sys.argv[1])
y2, _, old, to = read(sys.argv[2])
assert (y == y2).all()
good, bad = y == 0, y == 1
print(f"{int(good.sum())} good and {int(bad.sum())} defective parts; thresholds {tn:.4f} (new) and {to:.4f} (before)")
print("| | new | before |")
print("|---|---|---|")
print(f"| image AUROC | {auroc(y, new):.3f} | {auroc(y, old):.3f} |")
print(f"| good parts rejected | {100 * (new[good] > tn).mean():.1f} % | {100 * (old[good] > to).mean():.1f} % |")
print(f"| defective parts caught | {100 * (new[bad] > tn).mean():.1f} % | {100 * (old[bad] > to).mean():.1f} % |")
for t in sorted(set(types[bad])):
    m = bad & (types == t)
    print(f"| {t} ({int(m.sum())}) | {100 * (new[m] > tn).mean():.0f} % | {100 * (old[m] > to).mean():.0f} % |")
dc = []
for _ in range(1000):
    b = rng.integers(len(y), size=len(y))
    yb = y[b]
    dc.append((new[b][yb == 1] > tn).mean() - (old[b][yb == 1] > to).mean())
gain = paired_auroc_gains(y, types, old, new)[0]  # the project's paired bootstrap (good and defective apart)
print(f"\nnew - before: caught {100 * ((new[bad] > tn).mean() - (old[bad] > to).mean()):+.1f} points (SE "
      f"{100 * np.std(dc):.1f}), image AUROC {gain['gain']:+.3f} (SE {gain['se']:.3f})")
