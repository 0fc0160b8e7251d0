"""Would the station's drift monitor see the panel's change? Each set's frames (in dataset order, good and defective,
as a line sends them) through ``station.drift.DriftMonitor`` with the shipped file's trained range and the
station's defaults (window 50, margin 0.5): the share of windows out of range and the first warning; and each
statistic's median against the trained quartiles. Usage: PYTHONPATH=. python drift52.py NAME=DATA ..."""

from __future__ import annotations

import sys

import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.priors.frame_stats import STAT_NAMES
from station.datasets import load_split
from station.drift import DriftMonitor, trained_range

MODEL = "model/weights/default"

ck = load_checkpoint(MODEL)
cfg = ck.detector.config
rng = trained_range(ck.meta)
assert rng is not None
print("trained quartiles: " + ", ".join(f"{n} {rng.q1[n]:.3f}..{rng.q3[n]:.3f}" for n in STAT_NAMES
                                         if n in rng.median) + "\n")
print("| set | " + " | ".join(f"{n} (median)" for n in STAT_NAMES if n in rng.median)
      + " | windows out of range | first warning |")
print("|---|" + "---|" * (sum(n in rng.median for n in STAT_NAMES) + 2))
for arg in sys.argv[1:]:
    name, data = arg.split("=", 1)
    sp = load_split(data, "test", cfg.priors, cfg.input_shape, roi=cfg.roi, frame_aspect=cfg.frame_aspect,
                    progress=False)
    mon = DriftMonitor(rng)
    out, first = 0, None
    for s in sp.frame_stats:
        text = mon.update(s)
        out += mon.warning is not None
        if text and mon.warning is not None and first is None:
            first = text
    meds = [f"{np.median([getattr(s, n) for s in sp.frame_stats]):.3f}" for n in STAT_NAMES if n in rng.median]
    print(f"| {name} | " + " | ".join(meds) + f" | {out} of {len(sp.frame_stats)} | {first or ''} |")
