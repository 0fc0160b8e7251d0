"""The shipped file's variation model on seed 1173's good parts as rendered and through `station bench shift`'s
shifts: score, share of the part the highlight rule hides, noise level; then the ten parts whose score the first
shift raised most. Run from the repository root:

    PYTHONPATH=. python docs/results/2026-11-30-shifts-1173/highlights.py "exposure x1.3" "exposure x0.77"  # expo.txt
    PYTHONPATH=. python docs/results/2026-11-30-shifts-1173/highlights.py "dolp x0.5" "blur 1 px"           # dolp.txt
"""
import sys

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.shifts import Channels, shift
from station.evaluation import model_split

M = "model/weights/default"
ck = load_checkpoint(M)
var = ck.detector.variation
sp = model_split(ck, M, "data/line-panel-heldout-1173", "test")
good = np.flatnonzero(sp.label.numpy() == 0)
x = sp.priors.numpy()[good]
ch = Channels.of(ck.detector.config.priors)
out = {}
for name in ("none", *sys.argv[1:]):
    o = var.zmaps(torch.from_numpy(shift(name, x, ch)))
    out[name] = s, h, nz = o.scores.numpy(), o.highlight_fraction.numpy(), o.noise_level.numpy()
    print(f"{name:15s} score q50 {np.median(s):.2f} q99 {np.percentile(s, 99):.2f} max {s.max():.1f} | hidden q50 "
          f"{np.median(h):.3f} q99 {np.percentile(h, 99):.3f} max {h.max():.3f} | noise q50 {np.median(nz):.2f} "
          f"max {nz.max():.2f}")
(s0, h0, _), (s1, h1, _) = out["none"], out[sys.argv[1]]
for i in np.argsort(-(s1 - s0))[:10]:
    print(int(sp.index[good[i]]), f"score {s0[i]:.2f} -> {s1[i]:.2f}  hidden {h0[i]:.3f} -> {h1[i]:.3f}")
