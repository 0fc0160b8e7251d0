"""Feature check (no selection): the shipped file adapted to line-pv-val's good parts, with its shape check refitted
and with it switched off, on warp-val-1199 (a validation set): warped and good parts above each file's threshold.
Run from the repository's root after `station adapt ... --out runs/adapt-shape/adapted` (adapt.txt)."""

import copy

import numpy as np

from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.shape_check import ShapeCheck
from station.evaluation import load_and_evaluate

SRC, OFF = "runs/adapt-shape/adapted", "runs/adapt-shape/adapted-off"
ck = load_checkpoint(SRC)
det = copy.deepcopy(ck.detector)
det.variation.shape = ShapeCheck()  # as adapt left it before: no check
save_checkpoint(OFF, det, ck.threshold, "copy without shape check", None, {}, {})
for path in (SRC, OFF, "model/weights/default"):
    c, _, sp, _, ev = load_and_evaluate(path, "data/warp-val-1199", "val")
    types, lab = np.array(sp.defect_type), sp.label.numpy()
    rej = ev.scores > c.threshold
    print(path, "threshold", round(c.threshold, 4), "good rejected", int(rej[lab == 0].sum()), "/",
          int((lab == 0).sum()))
    for t in sorted(set(types[lab == 1])):
        m = types == t
        print("   ", t, int(rej[m].sum()), "/", int(m.sum()))
