"""Rule 13 (rule.md): rule 12's fit (blurred copies up to 1.5 px, each left out with its part) against the shipped fit
on held-out sets 202 and 212 under mild softness (a half-pixel move, blur 0.25 and 0.5 px, a 2-degree rotation),
thresholds from the validation set.

Usage: mild.py OUT.json, from the repository root (about 8 min on 2 cores)."""

from __future__ import annotations

import copy
import json
import sys

import numpy as np
import torch

sys.path.insert(0, "docs/results/2026-11-25-physical-anomalies")
from bootstrap import held_out

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import false_reject_threshold
from model.draem.shifts import Channels, shift
from station.evaluation import model_split

MODEL = "model/weights/default"
SHIFTS = ("none", "move 0.5 px", "blur 0.25 px", "blur 0.5 px", "rotate 2 deg")
ck = load_checkpoint(MODEL)
ch = Channels.of(ck.detector.config.priors)
shipped = copy.deepcopy(ck.detector.variation)
tr = model_split(ck, MODEL, "data/line-polar-train", "train", good_only=True)
candidate = copy.deepcopy(shipped)
candidate.fit(tr.priors, tr.object_mask, blur_copies_sigma=1.5)
fits = {"shipped": shipped, "blur-augmented": candidate}


def scores(model, priors: np.ndarray) -> np.ndarray:
    t = torch.from_numpy(priors)
    return np.concatenate([model.zmaps(t[i : i + 50]).scores.numpy() for i in range(0, len(t), 50)])


va = model_split(ck, MODEL, "data/line-polar-val", "val")
lv = va.label.numpy()
val = {k: scores(m, va.priors.numpy()) for k, m in fits.items()}
result: dict[str, dict] = {}
for prefix, data in (("202 ", "data/line-polar-heldout"), ("212 ", "data/line-polar-heldout-212")):
    ho = model_split(ck, MODEL, data, "test")
    lh, kh = ho.label.numpy(), np.array([t or "" for t in ho.defect_type])
    for name in SHIFTS:
        hs = {k: scores(m, shift(name, ho.priors.numpy(), ch)) for k, m in fits.items()}
        result[prefix + name] = held_out(lh, kh, hs, lv, val, prefix + name)
        for k in hs:
            t5 = false_reject_threshold(val[k][lv == 0], 0.05)
            result[prefix + name][k]["good_rejected_5"] = float((hs[k][lh == 0] > t5).mean())
cells = [k for k in result if not k.endswith("none")]
gains = [result[c]["blur-augmented"]["auroc"] - result[c]["shipped"]["auroc"] for c in cells]
more = [result[c]["blur-augmented"]["good_rejected_1"] - result[c]["shipped"]["good_rejected_1"] for c in cells]
result["rule 13"] = {
    "mean_auroc_gain": float(np.mean(gains)),
    "worst_auroc_gain": float(min(gains)),
    "worst_good_rejected_1_rise": float(max(more)),
    "f": bool(np.mean(gains) > 0 and min(gains) >= -0.01),
    "g": bool(max(more) <= 0.01),
}
print(result["rule 13"], flush=True)
json.dump(result, open(sys.argv[1], "w"), indent=1)
