"""After rule 45's outcome, on validation only (in-sample thresholds; nothing chosen): why X lost at 5 %, and the
same combination with each score put in units of its good parts' q-th percentile above their median instead of
their MAD. Usage: python after.py SCORES.npz (propose_fit.py's)."""

from __future__ import annotations

import sys

import numpy as np

from model.draem.metrics import auroc, false_reject_threshold

d = np.load(sys.argv[1])
lab, types = d["val_label"], d["val_type"]
g = lab == 0
b, t = d["val_box"], d["val_test"]


def mad(s: np.ndarray) -> np.ndarray:
    m = np.median(s[g])
    return (s - m) / (1.4826 * np.median(np.abs(s[g] - m)))


def tail(s: np.ndarray, q: float) -> np.ndarray:
    m = np.median(s[g])
    return (s - m) / (np.percentile(s[g], q) - m)


def report(name: str, s: np.ndarray) -> None:
    t1, t5 = false_reject_threshold(s[g], 0.01), false_reject_threshold(s[g], 0.05)
    row = [f"{name:12s} AUROC {auroc(lab, s):.3f} @1% {np.mean(s[~g] > t1):.0%} @5% {np.mean(s[~g] > t5):.0%}"]
    for ty in sorted(set(types[~g])):
        sel = g | (types == ty)
        row.append(f"{ty[:5]} {auroc(lab[sel], s[sel]):.3f}/{np.mean(s[types == ty] > t1):.0%}/"
                   f"{np.mean(s[types == ty] > t5):.0%}")
    print("  ".join(row))


print("good parts' robust scores (MAD units), 50/90/95/99th percentiles: window",
      np.percentile(mad(b)[g], [50, 90, 95, 99]).round(2), "test", np.percentile(mad(t)[g], [50, 90, 95, 99]).round(2))
report("C", b)
report("X (rule 45)", np.maximum(mad(b), mad(t)))
for q in (90, 95, 99):
    report(f"X, q{q} units", np.maximum(tail(b, q), tail(t, q)))
