"""Rule 50's screen (used sets only) from nets50.py's OUT.npz: the shipped cascade with each residual network
column as its second look (``cascade50.cascade``: rule 49's X, as ``ResidualDetector.look`` scores it).
Thresholds from the good validation parts, held fixed. Per held-out set and pooled: caught at 1 % and 5 %, image
AUROC, good parts rejected at 1 %; caught at 1 % per type. Usage: python screen50.py OUT.npz [COLUMN...]."""

from __future__ import annotations

import sys

import numpy as np
from cascade50 import cascade, good_val, held_sets

from model.draem.metrics import auroc, false_reject_threshold

d = np.load(sys.argv[1])
vg = good_val(d)
sets = held_sets(d)
cols = sys.argv[2:] or sorted({k[4:] for k in d.files if k.startswith("val_")} - {"window", "chi", "label", "type"})
types = sorted({t for s in sets for t in d[f"{s}_type"] if t})
print("| second look's network | " + " | ".join(f"{s}: 1 % / 5 %" for s in sets)
      + " | pooled: 1 % / 5 % / AUROC / good rejected at 1 % | " + " | ".join(types) + " |")
print("|---" * (len(sets) + 2 + len(types)) + "|")
for col in ("none", *cols):
    v = cascade(d, "val", col)
    t1, t5 = false_reject_threshold(v[vg], 0.01), false_reject_threshold(v[vg], 0.05)
    xs = [cascade(d, s, col) for s in sets]
    ys = [d[f"{s}_label"] for s in sets]
    row = [f"{np.mean(x[y == 1] > t1):.3f} / {np.mean(x[y == 1] > t5):.3f}" for x, y in zip(xs, ys, strict=True)]
    x, y, ty = np.concatenate(xs), np.concatenate(ys), np.concatenate([d[f"{s}_type"] for s in sets])
    print(f"| {col} | " + " | ".join(row) + f" | {np.mean(x[y == 1] > t1):.3f} / {np.mean(x[y == 1] > t5):.3f} / "
          f"{auroc(y, x):.3f} / {np.mean(x[y == 0] > t1):.3f} | "
          + " | ".join(f"{np.mean(x[ty == t] > t1):.3f}" for t in types) + " |")
