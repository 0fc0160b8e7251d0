"""Other ways to put the second look's two findings together (used sets only, from nets50.py's screen scores):
above the gate, the larger of the shipped score and f(shipped, network), each over its own 1 % threshold on the good
validation parts, for f = the larger (the file's), the mean, the root of the sum of squares, the larger plus 0.3
times the smaller, the geometric mean. Columns C (the shipped network) and X (three networks, more defects).
Thresholds from the good validation parts, held fixed; pooled over the held-out sets.
Usage: PYTHONPATH=. python combine50.py runs/r50/screen.npz."""

from __future__ import annotations

import sys
from collections.abc import Callable

import numpy as np
from cascade50 import findings, good_val, held_sets

from model.draem.metrics import auroc, false_reject_threshold

d = np.load(sys.argv[1])
vg = good_val(d)
sets = held_sets(d)


COMBINE: dict[str, Callable[[np.ndarray, np.ndarray], np.ndarray]] = {
    "larger (shipped)": np.maximum,
    "mean": lambda a, b: (a + b) / 2,
    "root of sum of squares": lambda a, b: np.hypot(np.maximum(a, 0), np.maximum(b, 0)),
    "larger + 0.3 smaller": lambda a, b: np.maximum(a, b) + 0.3 * np.minimum(a, b),
    "geometric mean": lambda a, b: np.sqrt(np.maximum(a, 1e-3) * np.maximum(b, 1e-3)),
}
y = np.concatenate([d[f"{s}_label"] for s in sets])
ty = np.concatenate([d[f"{s}_type"] for s in sets])
print("| network | f | caught at 1 % | at 5 % | image AUROC | good rejected at 1 % | dents at 1 % | scratches at 1 % |")
print("|---|---|---|---|---|---|---|---|")
for col in ("C", "X"):
    for name, f in COMBINE.items():
        def score(s: str, col: str = col, f: Callable = f) -> np.ndarray:
            a, b, g = findings(d, s, col)
            return np.where(g, np.maximum(a, f(a, b)), a)
        v = score("val")
        t1, t5 = false_reject_threshold(v[vg], 0.01), false_reject_threshold(v[vg], 0.05)
        x = np.concatenate([score(s) for s in sets])
        print(f"| {col} | {name} | {np.mean(x[y == 1] > t1):.3f} | {np.mean(x[y == 1] > t5):.3f} | "
              f"{auroc(y, x):.3f} | {np.mean(x[y == 0] > t1):.3f} | {np.mean(x[ty == 'dent'] > t1):.3f} | "
              f"{np.mean(x[ty == 'scratch'] > t1):.3f} |")
