"""Each part's window score under fit A (affine) against fit B (a flow after it), from flow52.py's OUT.npz, good
parts and defective parts of the validation and held-out sets, with each fit's 1 % threshold on the good
validation parts. Usage: PYTHONPATH=. python plot52.py OUT.npz PNG TITLE"""

from __future__ import annotations

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from model.draem.metrics import false_reject_threshold

path, png, title = sys.argv[1:4]
d = np.load(path)
sets = ("val", "h0", "h1")
vg = d["val_label"] == 0
fig, ax = plt.subplots(figsize=(6.4, 6.0))
lift = lambda v: np.log10(np.maximum(v, 0.0) + 1.0)  # noqa: E731  robust SD >= 0 on a log axis
for label, colour, name in ((0, "tab:blue", "good"), (1, "tab:red", "defective")):
    a = np.concatenate([d[f"A_{s}_window"][d[f"{s}_label"] == label] for s in sets])
    b = np.concatenate([d[f"B_{s}_window"][d[f"{s}_label"] == label] for s in sets])
    ax.scatter(lift(a), lift(b), s=6 if label else 10, alpha=0.35 if label else 0.8, c=colour, label=name)
ta = false_reject_threshold(d["A_val_window"][vg], 0.01)
tb = false_reject_threshold(d["B_val_window"][vg], 0.01)
ax.axvline(lift(ta), c="k", ls="--", lw=0.8, label=f"1 % thresholds (A {ta:.1f}, B {tb:.1f} robust SD)")
ax.axhline(lift(tb), c="k", ls="--", lw=0.8)
top = max(ax.get_xlim()[1], ax.get_ylim()[1])
ax.plot([0, top], [0, top], c="grey", lw=0.6)
ticks = np.array([0, 1, 3, 10, 30, 100, 300])
ax.set_xticks(lift(ticks), ticks)
ax.set_yticks(lift(ticks), ticks)
ax.set_xlabel("window score, A: affine registration (robust SD)")
ax.set_ylabel("window score, B: a flow after it (robust SD)")
ax.set_title(title, fontsize=10)
ax.legend(loc="upper left", fontsize=8)
fig.tight_layout()
fig.savefig(png, dpi=110)
