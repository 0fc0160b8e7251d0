"""Ask the second look's network below the gate too (used sets only, screen50.py's scores): the network's finding
joins (the larger of the two, each over its own 1 % threshold on the good validation parts) for every part whose
window score is above the window's threshold at Q of the good validation parts rejected (the file: Q = 5 %, its
gate; 100 %: every part); the second look's test keeps its own gate. Thresholds from the good validation parts,
held fixed; pooled over the held-out sets. Usage: PYTHONPATH=. python gate50.py runs/r50/screen.npz [COLUMN]."""

from __future__ import annotations

import sys

import numpy as np
from cascade50 import findings, good_val, held_sets

from model.draem.metrics import auroc, false_reject_threshold

d = np.load(sys.argv[1])
col = sys.argv[2] if len(sys.argv) > 2 else "C"
vg = good_val(d)
sets = held_sets(d)
y = np.concatenate([d[f"{s}_label"] for s in sets])
ty = np.concatenate([d[f"{s}_type"] for s in sets])
print(f"network column {col}\n\n| asked above the window's threshold at | caught at 1 % | at 5 % | image AUROC | "
      "good rejected at 1 % | dents at 1 % |\n|---|---|---|---|---|---|")
for q in (0.05, 0.1, 0.2, 0.5, 1.0):
    g = -np.inf if q == 1.0 else false_reject_threshold(d["val_window"][vg], q)

    def score(s: str, g: float = g) -> np.ndarray:
        a, b, _ = findings(d, s, col)
        return np.where(d[f"{s}_window"] > g, np.maximum(a, b), a)

    v = score("val")
    t1, t5 = false_reject_threshold(v[vg], 0.01), false_reject_threshold(v[vg], 0.05)
    x = np.concatenate([score(s) for s in sets])
    print(f"| {q:.0%} of good parts{' (the file)' if q == 0.05 else ''} | {np.mean(x[y == 1] > t1):.3f} | "
          f"{np.mean(x[y == 1] > t5):.3f} | {auroc(y, x):.3f} | {np.mean(x[y == 0] > t1):.3f} | "
          f"{np.mean(x[ty == 'dent'] > t1):.3f} |")
