"""The second look's network on defect types it never saw, from nets50.py's OUT.npz: for each defect type T, the
shipped cascade with no network (the file before rule 49), with a network that saw T (R: every type, seed 0) and
with the network trained without T (column H-T, same command and seed), each scored as the file scores it
(``cascade50.cascade``). Thresholds from the good validation parts, held fixed. Per type against all good
parts of the held-out sets (pooled; all, or those named): image AUROC and caught at 1 % and 5 %; and the whole
set with each network. Usage: python heldout50.py OUT.npz [SET...] (e.g. h0)."""

from __future__ import annotations

import sys

import numpy as np
from cascade50 import cascade, good_val, held_sets

from model.draem.metrics import auroc, false_reject_threshold

d = np.load(sys.argv[1])
vg = good_val(d)
sets = sys.argv[2:] or held_sets(d)


y = np.concatenate([d[f"{s}_label"] for s in sets])
ty = np.concatenate([d[f"{s}_type"] for s in sets])
kinds = sorted({t for t in ty if t})
print(f"sets {', '.join(sets)}: {int((y == 0).sum())} good, {int((y == 1).sum())} defective")


def figures(col: str, part: np.ndarray, good: bool = False) -> str:
    """Image AUROC / caught at 1 % / caught at 5 % of ``part`` against all good parts (``good``: and the good
    parts rejected at the 1 % threshold)."""
    v = cascade(d, "val", col)
    t1, t5 = false_reject_threshold(v[vg], 0.01), false_reject_threshold(v[vg], 0.05)
    x = np.concatenate([cascade(d, s, col) for s in sets])
    keep = (y == 0) | part
    return (f"{auroc(y[keep], x[keep]):.3f} / {np.mean(x[part] > t1):.0%} / {np.mean(x[part] > t5):.0%}"
            + (f" / {np.mean(x[y == 0] > t1):.1%}" if good else ""))


print("\nimage AUROC / caught at 1 % / caught at 5 %, each type against all good parts:\n")
print("| type | defective | no network | network that saw it (R) | network trained without it (H-T) |")
print("|---|---|---|---|---|")
for t in kinds:
    col = f"H-{t}"
    held = figures(col, ty == t) if f"val_{col}" in d.files else "(not trained)"
    print(f"| {t} | {int(np.sum(ty == t))} | {figures('none', ty == t)} | {figures('R', ty == t)} | {held} |")
print("\nall defective parts, each network:\n\n| network | image AUROC / caught at 1 % / caught at 5 % / good "
      "rejected at 1 % |\n|---|---|")
for col in [c for c in ("none", "R", *(f"H-{t}" for t in kinds), "C") if c == "none" or f"val_{c}" in d.files]:
    print(f"| {col} | {figures(col, y == 1, good=True)} |")
