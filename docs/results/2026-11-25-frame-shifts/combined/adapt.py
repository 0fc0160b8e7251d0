"""Does ``station adapt`` repair a line that differs from the renders in several small ways at once? The shipped
model adapted (``model.draem.adapt.adapt``, as ``station adapt`` does: normalisation and variation statistics
refitted on the line's good parts, cross-fitted threshold for 1 % of good parts rejected) on the good parts of
held-out set 212 changed by a shift, then judged on held-out set 202 changed by the same shift, against the model
unadapted at its own threshold. Shifts: none, and the four-way combination of the frame-shifts page.

Usage: adapt.py OUT.json, from the repository root (about 15 min on 2 cores)."""

from __future__ import annotations

import json
import sys

import torch

from model.draem.adapt import AdaptConfig, adapt, image_scores
from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import auroc
from model.draem.shifts import Channels, shift
from station.evaluation import model_split

MODEL = "model/weights/default"
SHIFTS = ("none", "dolp x0.7 & gamma 1.25 & blur 0.5 px & zoom x1.02")
ck = load_checkpoint(MODEL)
ch = Channels.of(ck.detector.config.priors)
line = model_split(ck, MODEL, "data/line-polar-heldout-212", "test")
good = line.label.numpy() == 0
ho = model_split(ck, MODEL, "data/line-polar-heldout", "test")
lh = ho.label.numpy()
result = {}
for name in SHIFTS:
    x_line = torch.from_numpy(shift(name, line.priors.numpy()[good], ch))
    adapted, res = adapt(ck.detector, x_line, line.object_mask[torch.from_numpy(good)], AdaptConfig(false_reject=0.01),
                         progress=False)
    x = torch.from_numpy(shift(name, ho.priors.numpy(), ch))
    rows = {}
    for label, det, threshold in (("unadapted", ck.detector, ck.meta["threshold"]),
                                  ("adapted", adapted, res.threshold.threshold)):
        s = image_scores(det, x)
        rows[label] = {"image_auroc": auroc(lh.astype(bool), s), "threshold": float(threshold),
                       "good_rejected": float((s[lh == 0] > threshold).mean()),
                       "caught": float((s[lh == 1] > threshold).mean())}
        print(f"{name} {label}: image AUROC {rows[label]['image_auroc']:.3f}, good rejected "
              f"{rows[label]['good_rejected']:.1%}, defective caught {rows[label]['caught']:.1%}", flush=True)
    rows["adapted_on"] = int(good.sum())
    result[name] = rows
json.dump(result, open(sys.argv[1], "w"), indent=1)
