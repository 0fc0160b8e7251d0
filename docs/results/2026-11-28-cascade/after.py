"""After rule 46's outcome, on validation only (in-sample thresholds; nothing chosen): why the cascade lost at 5 %.
The 5 % threshold is the (k+1)-th largest good score (``false_reject_threshold``), the good part at g5 itself; the
gate ``C_r >= g5`` let that part's second look raise it, and with it the threshold. Gated strictly (``C_r > g5``)
that part stays at g5. Usage: python after.py SCORES.npz (rule 45's ``propose_fit.py`` output)."""

from __future__ import annotations

import sys

import numpy as np

from model.draem.metrics import auroc, false_reject_threshold

d = np.load(sys.argv[1])
lab = d["val_label"]
g = lab == 0


def robust(s: np.ndarray) -> np.ndarray:
    med = np.median(s[g])
    return (s - med) / (1.4826 * np.median(np.abs(s[g] - med)))


c, t = robust(d["val_box"]), robust(d["val_test"])
g5 = false_reject_threshold(c[g], 0.05)
for name, x in (("C", c), ("X, gate >= g5 (rule 46)", np.where(c >= g5, np.maximum(c, t), c)),
                ("X, gate > g5", np.where(c > g5, np.maximum(c, t), c))):
    t1, t5 = false_reject_threshold(x[g], 0.01), false_reject_threshold(x[g], 0.05)
    print(f"{name:24s} AUROC {auroc(lab, x):.4f}  5 % threshold {t5:.3f} (g5 {g5:.3f})  caught at 1 % "
          f"{np.mean(x[~g] > t1):.1%}, at 5 % {np.mean(x[~g] > t5):.1%}")
