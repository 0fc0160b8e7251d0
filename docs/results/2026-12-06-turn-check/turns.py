"""Each part's registration turn (``VariationOutput.turn_deg``) from the shipped file, on the validation set of the
line as built (the set thresholds are chosen on) and on the turned-camera sets read before (development sets now:
seeds 1217-1226). Run from the repository's root; writes turns.json (per set: the good and the defective parts'
turns, degrees, and whether the shipped file rejected each) and prints turns.txt's lines."""
import json
import sys

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from station.datasets import load_split

SETS = (("square (validation)", 0, "data/line-pv-val", "val"), ("turned 3", 3, "data/turned3-1217", "test"),
        ("turned 4", 4, "data/turned4-1218", "test"), ("turned 8", 8, "data/turned8-1219", "test"),
        ("turned 12", 12, "data/turned12-1221", "test"), ("turned 20", 20, "data/turned20-1225", "test"),
        ("turned 30", 30, "data/turned30-1226", "test"))
ckpt = load_checkpoint("model/weights/default")
det = ckpt.detector
cfg = det.config
out = {}
for name, camera, path, split in SETS:
    sp = load_split(path, split, cfg.priors, cfg.input_shape, roi=cfg.roi, frame_aspect=cfg.frame_aspect,
                    dome_segments=cfg.dome_segments, around_px=cfg.around_px, progress=False)
    turns, scores = [], []
    with torch.no_grad():
        for i in range(0, len(sp.priors), 32):
            o = det.variation.zmaps(sp.priors[i:i + 32].float(), around=sp.around[i:i + 32].float())
            turns += o.turn_deg.tolist()
    bad = sp.label.numpy().astype(bool)
    t = np.array(turns)
    out[name] = {"camera_deg": camera, "good": [None if np.isnan(v) else float(v) for v in t[~bad]],
                 "defective": [None if np.isnan(v) else float(v) for v in t[bad]]}
    g = t[~bad & np.isfinite(t)]  # a part whose warp was not found reads no turn
    print(f"{name:20s} good {len(g):3d}: median {np.median(g):+6.2f}  p1 {np.percentile(g, 1):+6.2f}  "
          f"p99 {np.percentile(g, 99):+6.2f}  min {g.min():+6.2f} max {g.max():+6.2f}; defective median "
          f"{np.nanmedian(t[bad]):+6.2f}; no warp found {int(np.isnan(t).sum())} of {len(t)}", flush=True)
json.dump(out, open(sys.argv[1] if len(sys.argv) > 1 else "docs/results/2026-12-06-turn-check/turns.json", "w"))
