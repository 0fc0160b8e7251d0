"""Good parts of held-out set 202 (those among its first 120 parts, the first 60) under single and combined shifts:
the shipped variation model's image scores and frame noise levels. Usage: noise.py, from the repository root
(1 min); its output is noise.txt."""

import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.shifts import Channels, shift
from station.evaluation import model_split

MODEL = "model/weights/default"
SHIFTS = ("none", "dolp x0.7 & blur 0.5 px", "gamma 1.25", "blur 0.5 px", "zoom x1.02",
          "dolp x0.7 & gamma 1.25 & blur 0.5 px & zoom x1.02")
ck = load_checkpoint(MODEL)
vm, ch = ck.detector.variation, Channels.of(ck.detector.config.priors)
ho = model_split(ck, MODEL, "data/line-polar-heldout", "test", limit=120)
good = ho.priors.numpy()[ho.label.numpy() == 0][:60]
for name in SHIFTS:
    o = vm.zmaps(torch.from_numpy(shift(name, good, ch)))
    s, n = o.scores, o.noise_level
    print(f"{name:50s} score median {float(s.median()):.2f} p90 {float(s.quantile(0.9)):.2f}  "
          f"noise median {float(n.median()):.2f} max {float(n.max()):.2f}")
