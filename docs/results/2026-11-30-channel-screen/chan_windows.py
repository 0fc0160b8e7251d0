"""Per-channel window statistics of the shipped file's variation model (curvature of each channel's signed z, after
the frame's noise level), for the channel screen. Usage, from the repository root (writes runs/s72/cw-NAME.npz):
    PYTHONPATH=. python docs/results/2026-11-30-channel-screen/chan_windows.py pv data/line-pv-val val"""
import sys
import time

import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.variation import NOISE_CAP, curvature
from station.evaluation import model_split

M = "model/weights/default"
ck = load_checkpoint(M)
var = ck.detector.variation
region = var.scored_region()
name, data, split = sys.argv[1:4]
sp = model_split(ck, M, data, split)
ws, js = [], []
t = time.time()
for n, xi in enumerate(sp.priors.float().numpy()):
    r, coef, judged, _ = var._judged_residual(xi)
    z = var.used(var.clustered(r, coef))
    level = var.noise_level(np.abs(z), judged)
    z = z / (level if 1.0 < level <= NOISE_CAP else 1.0)
    w = np.stack([curvature(zc * judged, float(var.curvature_sigma)) for zc in z])
    ws.append(w.astype(np.float16))
    js.append(judged & region)
    if n % 100 == 0:
        print(n, f"{time.time() - t:.0f}s", flush=True)
np.savez_compressed(f"runs/s72/cw-{name}.npz", w=np.stack(ws), judged=np.stack(js), label=sp.label.numpy(),
                    dtype=np.array(sp.defect_type), index=np.array(sp.index),
                    loc=var.window_location.numpy(), spread=var.window_spread.numpy())
print(name, "done", z.shape, flush=True)
