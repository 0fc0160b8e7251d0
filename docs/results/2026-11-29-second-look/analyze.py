"""Rule 48's design figures from design.py's OUT.npz: for each candidate test statistic, the cascade of rule 47
(a part above the gate scores the larger of its window score and the statistic's score, each in robust SD over the
good validation parts), thresholds from the good validation parts held fixed; caught at 1 % and 5 % and image
AUROC per set, and pooled over the held-out sets; the good validation parts the second look raises above the
window's 1 % threshold. Usage: python analyze.py OUT.npz."""

from __future__ import annotations

import sys

import numpy as np

from model.draem.metrics import auroc, false_reject_threshold
from model.draem.second_look import robust_location_spread

d = np.load(sys.argv[1])
gate = float(d["gate"])
sets = sorted({k.split("_")[0] for k in d.files if k.endswith("_window")}, key=lambda s: (s != "val", s))
keys = sorted({k.split("_", 1)[1] for k in d.files if k.startswith("val_") and k not in
               ("val_window", "val_label", "val_type")})
vg = d["val_label"] == 0
units = {k: robust_location_spread(d[f"val_{k}"][vg]) for k in keys}


def cascade(name: str, key: str | None) -> np.ndarray:
    c = d[f"{name}_window"]
    if key is None:
        return c
    loc, spread = units[key]
    t = (np.nan_to_num(d[f"{name}_{key}"], nan=0.0) - loc) / spread
    return np.where(c > gate, np.maximum(c, t), c)


cands: list[str | None] = [None, *keys]
thr = {k: {fr: false_reject_threshold(cascade("val", k)[vg], fr) for fr in (0.01, 0.05)} for k in cands}
print(f"gate {gate:.2f} robust SD; window 1 % threshold on validation {thr[None][0.01]:.2f}")
print("| statistic | val thr 1 % | " + " | ".join(f"{s} caught 1 % / 5 % / AUROC" for s in sets[1:]) +
      " | pooled caught 1 % / 5 % / AUROC / good rej 1 % |")
for k in cands:
    row, pool_s, pool_y = [], [], []
    for s in sets[1:]:
        x, y = cascade(s, k), d[f"{s}_label"]
        pool_s.append(x)
        pool_y.append(y)
        row.append(f"{np.mean(x[y == 1] > thr[k][0.01]):.3f} / {np.mean(x[y == 1] > thr[k][0.05]):.3f} / "
                   f"{auroc(y, x):.3f}")
    x, y = np.concatenate(pool_s), np.concatenate(pool_y)
    print(f"| {k or 'window'} | {thr[k][0.01]:.2f} | " + " | ".join(row) +
          f" | {np.mean(x[y == 1] > thr[k][0.01]):.3f} / {np.mean(x[y == 1] > thr[k][0.05]):.3f} / "
          f"{auroc(y, x):.3f} / {np.mean(x[y == 0] > thr[k][0.01]):.3f} |")
types = sorted({t for s in sets[1:] for t in d[f"{s}_type"] if t})
print("\npooled held-out, caught at 1 % per type:")
print("| statistic | " + " | ".join(types) + " |")
for k in cands:
    x = np.concatenate([cascade(s, k) for s in sets[1:]])
    t = np.concatenate([d[f"{s}_type"] for s in sets[1:]])
    print(f"| {k or 'window'} | " + " | ".join(f"{np.mean(x[t == ty] > thr[k][0.01]):.3f}" for ty in types) + " |")
print("\ngood validation parts above the gate: window, then each statistic in robust SD")
c = d["val_window"][vg]
for i in np.argsort(-c)[: int((c > gate).sum())]:
    print(f"{c[i]:6.1f}  " + "  ".join(f"{k} {(d[f'val_{k}'][vg][i] - units[k][0]) / units[k][1]:6.1f}"
                                      for k in keys))
