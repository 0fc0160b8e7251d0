"""The shipped file's variation model on seed 1173's good parts as rendered and through `station bench shift`'s
DoLP x0.5 and blur 1 px: score, share of the part the highlight rule hides, noise level (stdout: dolp.txt). Run from the
repository root."""
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
for name in ("none", "dolp x0.5", "blur 1 px"):
    xs = torch.from_numpy(shift(name, x, ch))
    o = var.zmaps(xs)
    out[name] = (o.scores.numpy(), o.highlight_fraction.numpy(), o.noise_level.numpy())
    s, h, nz = out[name]
    print(f"{name:15s} score q50 {np.median(s):.2f} q99 {np.percentile(s, 99):.2f} max {s.max():.1f} | hidden q50 "
          f"{np.median(h):.3f} q99 {np.percentile(h, 99):.3f} max {h.max():.3f} | noise q50 {np.median(nz):.2f} "
          f"max {nz.max():.2f}")
s0, h0, _ = out["none"]
s1, h1, _ = out["dolp x0.5"]
top = np.argsort(-(s1 - s0))[:10]
for i in top:
    print(int(sp.index[good[i]]), f"score {s0[i]:.2f} -> {s1[i]:.2f}  hidden {h0[i]:.3f} -> {h1[i]:.3f}")
