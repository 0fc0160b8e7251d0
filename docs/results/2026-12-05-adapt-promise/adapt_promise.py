"""Does the 1 % threshold `station adapt` sets on 200 good parts keep its promise on 300 more?
(docs/results/2026-12-05-adapt-promise.md; nothing selected on it)

Fresh seed 1205's line as built (600 parts, 15 % defective, every part test; data/line-good-1205). The first 200 good
parts in index order adapt the shipped file (`model.draem.adapt.adapt`, as `station adapt` does: cross-fitted, 1 %,
the checks' floor on); every other part is judged by the adapted file (its threshold) and by the shipped file (its
own). Prints the adapted threshold and its promise (the expected share of new good parts above it, (k + 1) / (n + 1),
and its one-sided 95 % bound, from the held-out scores adapt chose it on), then per file the judged good parts
rejected with a two-sided 95 % interval, defective parts caught (all, per kind), and each good part rejected with what
rejected it. Run from the repository's root."""

import numpy as np
import torch

from model.draem.adapt import AdaptConfig, adapt, image_scores
from model.draem.checkpoint import load_checkpoint
from model.draem.rate_bounds import expected_rate, interval, upper_bound
from station.evaluation import model_split

MODEL, SET, N_ADAPT = "model/weights/default", "data/line-good-1205", 200
ck = load_checkpoint(MODEL)
sp = model_split(ck, MODEL, SET, "test")
x = sp.priors.float()
label = sp.label.numpy() == 1
good = np.flatnonzero(~label)
fit = torch.from_numpy(good[:N_ADAPT])
judged = np.setdiff1d(np.arange(len(label)), good[:N_ADAPT])
lab = label[judged]
kinds = np.array([sp.defect_type[i] or "" for i in judged])
names = sorted(set(kinds[lab]))
det, res = adapt(ck.detector, x[fit], sp.object_mask[fit], AdaptConfig(), progress=False)
k = int((res.heldout_scores > res.threshold.threshold).sum())
n = int(res.n_heldout)
print(f"adapted on {len(fit)} good parts: threshold {res.threshold.threshold:.4f} ({res.threshold.rule}); {k} of {n} "
      f"held-out scores above it: promise {100 * expected_rate(k, n):.2f} %, at most {100 * upper_bound(k, n):.2f} % "
      f"at 95 %; {res.shape}")
print(f"judged: {int((~lab).sum())} good parts (none adapted on), {int(lab.sum())} defective "
      f"({', '.join(f'{c} {int((kinds[lab] == c).sum())}' for c in names)})")
print("| file | threshold | good parts rejected | 95 % interval | defective caught | "
      + " | ".join(names) + " |\n|---|---|---|---|---|" + "---|" * len(names))
files = (("shipped file", ck.detector, ck.threshold), (f"adapted on {N_ADAPT}", det, res.threshold.threshold))
for name, d, thr in files:
    s = image_scores(d, x[torch.from_numpy(judged)])
    rej = s > thr
    kg, ng = int(rej[~lab].sum()), int((~lab).sum())
    lo, hi = interval(kg, ng)
    print(f"| {name} | {thr:.4f} | {kg} of {ng} ({100 * kg / ng:.1f} %) | {100 * lo:.1f}-{100 * hi:.1f} % | "
          f"{int(rej[lab].sum())} of {int(lab.sum())} ({100 * rej[lab].mean():.1f} %) | "
          + " | ".join(f"{int(rej[lab & (kinds == c)].sum())}/{int((lab & (kinds == c)).sum())}" for c in names)
          + " |", flush=True)
    which = np.flatnonzero(rej & ~lab)
    if len(which):
        out = d.variation.zmaps(x[torch.from_numpy(judged[which])])
        for j, i in enumerate(which):
            print(f"  {name}: part {int(judged[i])} score {s[i]:.4f}; window {float(out.scores[j]):.3f}, "
                  f"bend {float(out.edge_bend[j]):.3f}, step {float(out.edge_step[j]):.3f}")
