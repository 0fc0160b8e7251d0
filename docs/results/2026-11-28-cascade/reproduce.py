"""The model's own second look (``station variation --second-look``, ``model.draem.second_look``) against rule 47's
script scores (``decide47.py``'s X) on a set: each part's variation score in robust SD of the validation good
parts' window scores, the same units as the script's. Usage: python reproduce.py MODEL SCORES.npz DATA SPLIT NAME
(NAME: the set's prefix in SCORES.npz, val or heldout0)."""

from __future__ import annotations

import sys

import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

model, scores, data, split, name = sys.argv[1:]
d = np.load(scores)
vgood = d["val_label"] == 0
ck = load_checkpoint(model)
vm = ck.detector.variation
sp = model_split(ck, model, data, split)
own = np.concatenate([vm.zmaps(sp.priors[i:i + 50].float()).scores.numpy() for i in range(0, len(sp.index), 50)])
med = np.median(d["val_box"][vgood])
mad = 1.4826 * np.median(np.abs(d["val_box"][vgood] - med)) + 1e-9
c, t = (d[f"{name}_box"] - med) / mad, d[f"{name}_test"]
tm = np.median(d["val_test"][vgood])
t = (t - tm) / (1.4826 * np.median(np.abs(d["val_test"][vgood] - tm)) + 1e-9)
g5 = float(vm.second_look.calibration[0])
script = np.where(c > g5, np.maximum(c, t), c)
mine = (own - med) / mad
looked = c > g5
err = np.abs(mine - script)
print(f"{name}: {len(mine)} parts, {int(looked.sum())} looked at again; gate {g5:.4f}; max |model - script| in robust "
      f"SD: not looked at {err[~looked].max():.2e}, looked at {err[looked].max():.2e}")
rel = err / np.maximum(np.abs(script), 1.0)
print(f"relative to the score (or 1 SD): largest {rel.max():.2e}, within float16 rounding (4.9e-4; the model keeps its "
      f"references in float16, the script in float32)")
if name == "val":
    from model.draem.metrics import auroc, false_reject_threshold

    lab = d["val_label"]
    for what, s in (("script", script), ("model", mine)):
        t1, t5 = false_reject_threshold(s[lab == 0], 0.01), false_reject_threshold(s[lab == 0], 0.05)
        print(f"{what}: AUROC {auroc(lab, s):.4f}, caught at 1 % {np.mean(s[lab == 1] > t1):.3f}, "
              f"at 5 % {np.mean(s[lab == 1] > t5):.3f}")
