"""What the look network buys per kind at 1 % of good parts rejected (docs/results/2026-12-06-look-share.md; sets read
before, nothing chosen on it): the shipped file's decision against its variation model's window alone, each thresholded
on the same 370 good validation parts (the window's in its own units by ``false_reject_threshold``, the count
``choose_threshold`` uses).

Usage: python look_share.py SET:SPLIT ... (run from the repository's root)."""
import sys

import numpy as np

from model.draem.adapt import image_scores
from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import choose_threshold, false_reject_threshold
from station.datasets import load_split

ck = load_checkpoint("model/weights/default")
cfg = ck.detector.config


def scores(arg: str):
    path, split = arg.split(":")
    sp = load_split(path, split, cfg.priors, cfg.input_shape, roi=cfg.roi, frame_aspect=cfg.frame_aspect,
                    dome_segments=cfg.dome_segments, around_px=cfg.around_px, progress=False)
    x = sp.priors.float()
    around = None if sp.around is None else sp.around.float()
    s = image_scores(ck.detector, x, around=around)
    w = ck.detector.variation.zmaps(x, around=around).scores.numpy()
    return sp.label.numpy() == 1, np.array(sp.defect_type), np.asarray(s), w


lab, _, s, w = scores("data/line-pv-val:val")
ft = choose_threshold(lab, s).threshold
wt = false_reject_threshold(w[~lab], 0.01)  # the same count as choose_threshold, in the window's units
print(f"val: file threshold {ck.threshold:.4f} (chosen again {ft:.4f}); window alone {wt:.3f}", flush=True)
for arg in sys.argv[1:]:
    lab, kinds, s, w = scores(arg)
    a, b = s > ck.threshold, w > wt
    print(f"\n{arg}: good rejected file {a[~lab].sum()} / window alone {b[~lab].sum()} of {(~lab).sum()}")
    for k in ["all", *sorted(set(kinds[lab]))]:
        sel = lab & ((kinds == k) if k != "all" else True)
        print(f"  {k:14s} {sel.sum():4d}: file {a[sel].sum():4d} ({100 * a[sel].mean():5.1f} %), window alone "
              f"{b[sel].sum():4d} ({100 * b[sel].mean():5.1f} %), both {(a & b)[sel].sum()}, file only "
              f"{(a & ~b)[sel].sum()}, window only {(~a & b)[sel].sum()}", flush=True)
