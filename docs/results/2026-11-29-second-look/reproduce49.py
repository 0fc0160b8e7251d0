"""The model's own rule 49 against the script's, on the validation set: MODEL's variation scores (the residual
networks as its second look, ``Detector.residual_look``), in the window's robust SD, against ``decide48.py``'s X
from nets.py's OUT.npz (there in units of the shipped score's 1 % threshold, so times it); and whether MODEL's
network is the rule's (runs/r48/res-all.pt). Usage: PYTHONPATH=. python reproduce49.py MODEL OUT.npz"""

from __future__ import annotations

import sys

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import auroc, false_reject_threshold
from model.draem.second_look import robust_location_spread
from station.evaluation import model_split

model, npz = sys.argv[1:]
ck = load_checkpoint(model)
det = ck.detector
rule = load_checkpoint("runs/r48/res-all").detector
same = all(torch.equal(a, b) for a, b in zip(det.residual.state_dict().values(),
                                             rule.residual.state_dict().values(), strict=True)
           if a.dtype != torch.float64)
print(f"{model}'s network is rule 49's, weight for weight: {same}")
sp = model_split(ck, model, "data/line-panel-val", "val")
_, wl, ws = (float(c) for c in det.variation.second_look.calibration[:3])
mine = np.concatenate([(det.predict(sp.priors[i:i + 50].float()).member_scores["variation"].double().numpy() - wl)
                       / ws for i in range(0, len(sp.priors), 50)])
d = np.load(npz)
vg = d["val_label"] == 0
gate = float(d["gate"])
s = np.where(d["val_window"] > gate, np.maximum(d["val_window"], d["val_chi"]), d["val_window"])
loc, spread = robust_location_spread(d["val_all_logit"][vg])
n = (d["val_all_logit"] - loc) / spread
ts, tn = false_reject_threshold(s[vg], 0.01), false_reject_threshold(n[vg], 0.01)
script = np.where(d["val_window"] > gate, np.maximum(s / ts, n / tn), s / ts) * ts
asked = d["val_window"] > gate
diff = np.abs(mine - script)
print(f"validation: {len(mine)} parts, {int(asked.sum())} above the gate")
print(f"  not asked: max |model - script| {diff[~asked].max():.3g} robust SD")
print(f"  asked:     max |model - script| {diff[asked].max():.3g} robust SD (scores up to {script.max():.0f})")
y = d["val_label"]
for name, v in (("model", mine), ("script", script)):
    t1 = false_reject_threshold(v[vg], 0.01)
    print(f"  {name}: AUROC {auroc(y, v):.4f}, caught at its 1 % threshold {np.mean(v[y == 1] > t1):.4f}")
