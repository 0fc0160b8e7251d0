"""Which check rejected the good parts in turned_adapt.py's upright run (nothing selected on it): the shipped file and
the file adapted on the same 90 upright good parts of seed 1196, each good part judged there that its own threshold
rejects, with its window score, the largest of its window map, the shape check's bend and the outline check's step
(each in units of its own threshold: above 1 rejects). Run from the repository's root."""

import numpy as np
import torch

from model.draem.adapt import AdaptConfig, adapt, image_scores
from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL, DATA = "model/weights/default", "data/line-heldout-1196"
ck = load_checkpoint(MODEL)
sp = model_split(ck, MODEL, DATA, "test")
x, label = sp.priors.float(), sp.label.numpy() == 1
good = np.flatnonzero(~label)
fit, judged = torch.from_numpy(good[0::2]), good[1::2]
adapted, result = adapt(ck.detector, x[fit], sp.object_mask[fit], AdaptConfig(), progress=False)
for name, det, thr in (("shipped", ck.detector, ck.threshold), ("adapted", adapted, result.threshold.threshold)):
    xs = x[torch.from_numpy(judged)]
    s, out = image_scores(det, xs), det.variation.zmaps(xs)
    peak = out.maps.flatten(1).max(1).values.numpy()
    for i in np.flatnonzero(s > thr):
        print(f"{name}: part {int(judged[i])} score {s[i]:.4f} > {thr:.4f}; window score {float(out.scores[i]):.3f}, "
              f"map max {peak[i]:.3f}, bend {float(out.edge_bend[i]):.3f}, step {float(out.edge_step[i]):.3f}")
