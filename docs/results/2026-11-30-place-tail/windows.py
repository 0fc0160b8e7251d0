"""Each part's raw window statistic w (before the per-place location and spread), for the per-place tail screen.

Usage (repository root; writes runs/a64/w-<name>.npz):
    python docs/results/2026-11-30-place-tail/windows.py pf:data/line-pf-val:val pv:data/line-pv-val:val
"""

import sys

import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

M = "model/weights/default"
ck = load_checkpoint(M)
var = ck.detector.variation
region = var.scored_region()
for name, data, split in (a.split(":") for a in sys.argv[1:]):
    sp = model_split(ck, M, data, split)
    ws, js = [], []
    for xi in sp.priors.float().numpy():
        r, coef, judged, _ = var._judged_residual(xi)
        w, _ = var.window(var.clustered(r, coef), judged)
        ws.append(w.astype(np.float16))
        js.append(judged & region)
    np.savez_compressed(f"runs/a64/w-{name}.npz", w=np.stack(ws), judged=np.stack(js), label=sp.label.numpy(),
                        dtype=np.array(sp.defect_type), index=np.array(sp.index),
                        loc=var.window_location.numpy(), spread=var.window_spread.numpy())
    print(name, "done", flush=True)
