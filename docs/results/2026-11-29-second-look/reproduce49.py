"""The model's own rule 49 against the script's, on the validation set. The rule's network (runs/r48/res-all.pt) is
put into the file before (model/weights/default before this change: FILE_BEFORE) as the product does it
(``ResidualDetector.look`` calibrated by ``calibrate_look`` on the good validation parts); its variation scores
(``Detector.residual_look``), in the window's robust SD, are put against ``decide48.py``'s X from nets.py's OUT.npz
(there in units of the shipped score's 1 % threshold, so times it). Then MODEL (the shipped file: the same recipe's
network trained again, not the rule's) the same way. Usage: PYTHONPATH=. python reproduce49.py FILE_BEFORE MODEL
OUT.npz"""

from __future__ import annotations

import sys

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.detector import Detector
from model.draem.metrics import auroc, false_reject_threshold
from model.draem.second_look import robust_location_spread
from model.draem.with_variation import calibrate_look
from station.evaluation import model_split

before, model, npz = sys.argv[1:]
ck = load_checkpoint(before)
rule = load_checkpoint("runs/r48/res-all").detector
det = Detector(ck.detector.config.with_(residual_members=1), ck.detector.normalizer)
det.load_state_dict({**ck.detector.state_dict(), **{k: v for k, v in rule.state_dict().items()
                                                     if k.startswith("residual.")}})
det.eval()
sp = model_split(ck, before, "data/line-panel-val", "val")
calibrate_look(det, sp.priors[sp.label == 0].float())
shipped = load_checkpoint(model).detector
same = all(torch.equal(a, b) for a, b in zip(shipped.residual.members.state_dict().values(),
                                             rule.residual.members.state_dict().values(), strict=True))
_, wl, ws = (float(c) for c in det.variation.second_look.calibration[:3])


def robust(d: Detector) -> np.ndarray:
    return np.concatenate([(d.predict(sp.priors[i:i + 50].float()).member_scores["variation"].double().numpy() - wl)
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
y = d["val_label"]
print(f"validation: {len(y)} parts, {int(asked.sum())} above the gate; look of the rule's network in the product: "
      f"{[round(float(v), 4) for v in det.residual.look]}")
for name, mine in (("the rule's network in the product", robust(det)),
                   (f"{model} (its network is the rule's, weight for weight: {same})", robust(shipped))):
    diff = np.abs(mine - script)
    print(f"{name}:\n  not asked: max |model - script| {diff[~asked].max():.3g} robust SD")
    print(f"  asked:     max |model - script| {diff[asked].max():.3g} robust SD (scores up to {script.max():.0f})")
    for what, v in (("model", mine), ("script", script)):
        t1 = false_reject_threshold(v[vg], 0.01)
        print(f"  {what}: AUROC {auroc(y, v):.4f}, caught at its 1 % threshold {np.mean(v[y == 1] > t1):.4f}")
