"""Does `station adapt` on a turned line's good parts win back what the turn costs? (nothing selected on it)

Seed 1196's held-out line (400 parts, 179 good; the set whose `station bench shift` reading showed the cost,
docs/results/2026-12-05-outline-shift.md), every part turned 5 degrees as the bench turns it
(`model.draem.shifts.shift("rotate 5 deg")`). The good parts are split by their place in the set: the even ones adapt
the shipped file (`model.draem.adapt.adapt`, as `station adapt` does, cross-fitted threshold at 1 %), the odd ones
and every defective part are judged, by the shipped file (its threshold) unturned and turned, and by the adapted file
(its own threshold) turned. With `upright` as its argument the same with nothing turned (the adapted file adapted on
upright parts: whether its threshold keeps its promise on an upright line). Run from the repository's root; prints
the table, then each judged good part a file rejects with what rejected it: its window score, the largest of its
window map, the shape check's bend and the outline check's step (each check's in units of its own threshold: above 1
rejects)."""

import sys

import numpy as np
import torch

from model.draem.adapt import AdaptConfig, adapt, image_scores
from model.draem.checkpoint import load_checkpoint
from model.draem.shifts import Channels, shift
from station.evaluation import model_split

MODEL, DATA = "model/weights/default", "data/line-heldout-1196"
ck = load_checkpoint(MODEL)
sp = model_split(ck, MODEL, DATA, "test")
x = sp.priors.float()
upright = sys.argv[1:] == ["upright"]
turned = x if upright else torch.from_numpy(shift("rotate 5 deg", x.numpy(), Channels.of(ck.detector.config.priors)))
label = sp.label.numpy() == 1
good = np.flatnonzero(~label)
fit, judged_good = good[0::2], good[1::2]
judged = np.concatenate([judged_good, np.flatnonzero(label)])
adapted, result = adapt(ck.detector, turned[torch.from_numpy(fit)], sp.object_mask[torch.from_numpy(fit)],
                        AdaptConfig(), progress=False)
var = adapted.variation
how = "upright" if upright else "turned"
print(f"adapted on {len(fit)} {how} good parts: threshold {result.threshold.threshold:.4f} ({result.threshold.rule}); "
      f"shape check {'on' if var.shape.fitted else 'off'}, outline check {'on' if var.outline.fitted else 'off'}; "
      f"{result.shape or ''}")
rows = (("shipped file, unturned", ck.detector, x, ck.threshold),
        ("shipped file, turned 5 deg", ck.detector, turned, ck.threshold),
        ("adapted on turned good parts, turned 5 deg", adapted, turned, result.threshold.threshold))
if upright:
    rows = (rows[0], ("adapted on upright good parts, upright", adapted, x, result.threshold.threshold))
lab = label[judged]
print(f"judged: {len(judged_good)} good parts (none adapted on), {int(lab.sum())} defective")
print("| file, frames | threshold | good parts rejected | defective caught |\n|---|---|---|---|")
rejected_good = []
for name, det, frames, thr in rows:
    s = image_scores(det, frames[torch.from_numpy(judged)])
    rej = s > thr
    print(f"| {name} | {thr:.4f} | {int(rej[~lab].sum())} of {int((~lab).sum())} | "
          f"{int(rej[lab].sum())} of {int(lab.sum())} ({100 * rej[lab].mean():.1f} %) |", flush=True)
    rejected_good.append((name, det, frames, thr, s, np.flatnonzero(rej & ~lab)))
for name, det, frames, thr, s, which in rejected_good:
    out = det.variation.zmaps(frames[torch.from_numpy(judged[which])])
    peak = out.maps.flatten(1).max(1).values.numpy()
    for k, i in enumerate(which):
        print(f"{name}: part {int(judged[i])} score {s[i]:.4f} > {thr:.4f}; window score {float(out.scores[k]):.3f}, "
              f"map max {peak[k]:.3f}, bend {float(out.edge_bend[k]):.3f}, step {float(out.edge_step[k]):.3f}")
