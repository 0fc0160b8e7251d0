"""Does flooring `station adapt`'s refitted check thresholds at the trained file's keep an adapted file's good parts
rejected near its 1 %, and what does it cost? (docs/results/2026-12-05-adapt-floor.md; nothing selected on it)

Fresh seed 1203's line as built (600 parts, 30 % defective, every part test). Good parts in index order: those at
even places adapt the shipped file (`model.draem.adapt.adapt`, as `station adapt` does: cross-fitted, 1 %), the first
N of them for N in 90 and 200, with `AdaptConfig.floor_checks` off and on; those at odd places and every defective
part are judged, by the shipped file (its threshold) and by each adapted file (its own). Run from the repository's
root; prints what each adaptation said, the table, defective parts caught per kind,
then each judged good part a file rejects with what rejected it: its window score, the largest of its window map, the
shape check's bend and the outline check's step (each in units of its own threshold: above 1 rejects).

With `turned` as its argument, docs/results/2026-12-05-turned-line.md: the same parts rendered with the camera turned
5 degrees (data/line-good-1203-turned5), adapted on the first 200 only, and the shipped file also judging the square
frames of the same parts."""

import sys

import numpy as np
import torch

from model.draem.adapt import AdaptConfig, adapt, image_scores
from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL, SQUARE, TURNED = "model/weights/default", "data/line-good-1203", "data/line-good-1203-turned5"
turned = sys.argv[1:] == ["turned"]
ck = load_checkpoint(MODEL)
sp = model_split(ck, MODEL, TURNED if turned else SQUARE, "test")
x = sp.priors.float()
label = sp.label.numpy() == 1
frames = {"": x}
rows = [("shipped file", ck.detector, ck.threshold, "")]
paired = np.ones(len(label), bool)
if turned:  # the same parts seen square: the shipped file on them too
    square = model_split(ck, MODEL, SQUARE, "test")
    assert square.index == sp.index
    paired = square.label.numpy() == sp.label.numpy()  # a defect seen by one camera and not the other: left out
    print(f"{int((~paired).sum())} parts whose defect one camera sees and the other does not: "
          f"{np.flatnonzero(~paired).tolist()} (left out)")
    frames["square"] = square.priors.float()
    rows = [("shipped file, square frames", ck.detector, ck.threshold, "square"),
            ("shipped file, turned frames", ck.detector, ck.threshold, "")]
good = np.flatnonzero(~label & paired)
adapting, judged_good = good[0::2], good[1::2]
judged = np.concatenate([judged_good, np.flatnonzero(label & paired)])
lab = label[judged]
kinds = np.array([sp.defect_type[i] for i in judged])
names = sorted(set(kinds[lab]))
for n in (200,) if turned else (90, 200):
    fit = torch.from_numpy(adapting[:n])
    for floor in (False, True):
        det, res = adapt(ck.detector, x[fit], sp.object_mask[fit], AdaptConfig(floor_checks=floor), progress=False)
        name = f"adapted on {len(fit)}, floor {'on' if floor else 'off'}"
        print(f"{name}: threshold {res.threshold.threshold:.4f}; {res.shape}", flush=True)
        rows.append((name, det, res.threshold.threshold, ""))
print(f"judged: {len(judged_good)} good parts (none adapted on), {int(lab.sum())} defective "
      f"({', '.join(f'{k} {int((kinds[lab] == k).sum())}' for k in names)})")
print("| file | threshold | good parts rejected | defective caught |\n|---|---|---|---|")
results = []
for name, det, thr, seen in rows:
    s = image_scores(det, frames[seen][torch.from_numpy(judged)])
    rej = s > thr
    print(f"| {name} | {thr:.4f} | {int(rej[~lab].sum())} of {int((~lab).sum())} | "
          f"{int(rej[lab].sum())} of {int(lab.sum())} ({100 * rej[lab].mean():.1f} %) |", flush=True)
    results.append((name, det, thr, seen, s, rej))
print("\ndefective parts caught per kind\n| file | " + " | ".join(names) + " |\n|---|" + "---|" * len(names))
for name, _, _, _, _, rej in results:
    print(f"| {name} | " + " | ".join(f"{int(rej[lab & (kinds == k)].sum())}/{int((lab & (kinds == k)).sum())}"
                                      for k in names) + " |")
print()
for name, det, thr, seen, s, rej in results:
    which = np.flatnonzero(rej & ~lab)
    if len(which) == 0:
        continue
    out = det.variation.zmaps(frames[seen][torch.from_numpy(judged[which])])
    peak = out.maps.flatten(1).max(1).values.numpy()
    for k, i in enumerate(which):
        print(f"{name}: part {int(judged[i])} score {s[i]:.4f} > {thr:.4f}; window score {float(out.scores[k]):.3f}, "
              f"map max {peak[k]:.3f}, bend {float(out.edge_bend[k]):.3f}, step {float(out.edge_step[k]):.3f}")
