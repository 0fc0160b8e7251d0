"""Where a blurred good part's score comes from: on 60 good held-out parts, the shipped variation model's score, the
frame's noise level, where on the part its largest window lies (within 4 px of the judged region's edge or not) and
the mean |z| per channel, for the unchanged frames and two blurs (model.draem.shifts).

Usage: edges.py, from the repository root."""

from __future__ import annotations

import cv2
import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.shifts import Channels, shift
from station.evaluation import model_split

ck = load_checkpoint("model/weights/default")
vm = ck.detector.variation
sp = model_split(ck, "model/weights/default", "data/line-polar-heldout", "test", 120)
x = sp.priors.numpy()[sp.label.numpy() == 0][:60]
ch = Channels.of(ck.detector.config.priors)
region = vm.region.numpy()
edge = region & ~cv2.erode(region.astype(np.uint8), np.ones((9, 9), np.uint8)).astype(bool)
for name in ("none", "blur 0.5 px", "blur 1 px"):
    out = vm.zmaps(torch.from_numpy(shift(name, x, ch)), signed=True)
    scores, maps = out.scores.numpy(), out.maps.numpy()
    at_edge = np.mean([edge[np.unravel_index(m.argmax(), m.shape)] for m in maps])
    z, judged = np.abs(out.signed.numpy()), out.judged.numpy()
    per_channel = [round(float(z[:, c][judged].mean()), 2) for c in range(z.shape[1])]
    print(
        f"{name:12s} score median {np.median(scores):.2f}, 90th percentile {np.percentile(scores, 90):.2f}; noise "
        f"level median {np.median(out.noise_level.numpy()):.2f}; largest window at the region's edge "
        f"{at_edge:.0%}; mean |z| per channel (intensity, DoLP, S1, S2) {per_channel}"
    )
