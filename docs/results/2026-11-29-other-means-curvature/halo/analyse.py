"""Halo screen's table: for each growth, the validation set's 1 % threshold (the highest score that flags at most 1 %
of its 370 good parts, as ``station threshold`` chooses), what it catches there, and the good parts it rejects on
check 61's sets (S: as built; G and R from check 61, 5 px; 8 and 11 px from run.sh).
Usage: python analyse.py HALO_RUNS C61_RUNS"""
import sys

import numpy as np

from model.draem.metrics import auroc
from station.errors import UserError
from station.eval_compare import read_scores

halo, c61 = sys.argv[1:3]


def read(folder):
    """(labels, scores, defect types) of a report's parts (``read_scores``); UserError when it has none."""
    label, kind, score = zip(*read_scores(folder).values(), strict=True)
    return np.array(label), np.array(score), np.array(kind)


print("| growth (input px) | val: AUROC | val: caught at 1 % | dents / scratches | R: good rejected |"
      " G: good rejected |")
print("|---|---|---|---|---|---|")
for g in (5, 8, 11):
    try:
        y, s, t = read(f"{halo}/eval-{g}-val")
    except UserError:
        continue
    good = np.sort(s[y == 0])[::-1]
    th = good[int(np.floor(0.01 * len(good)))]  # flags the scores above it: at most 1 % of good parts
    out = [f"{100 * (s[(y == 1) & (t == k)] > th).mean():.0f} %" for k in ("dent", "scratch")]
    other = []
    for k in ("R", "G"):
        folder = f"{c61}/eval-K3-{k}" if g == 5 else f"{halo}/eval-{g}-{k}"
        try:
            yk, sk, _ = read(folder)
            other.append(f"{100 * (sk[yk == 0] > th).mean():.1f} %")
        except UserError:
            other.append("(not run)")
    print(f"| {g} | {auroc(y, s):.3f} | {100 * (s[y == 1] > th).mean():.1f} % | {' / '.join(out)} |"
          f" {' | '.join(other)} |")
