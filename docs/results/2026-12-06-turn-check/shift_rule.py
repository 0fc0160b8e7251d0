"""Which registration warps the old shift rule (the warp's translation, its shift at the view's top left corner) and
the new one (the shift of the view's centre) throw away, on the validation set of the line as built, two square
held-out sets read before, and the turned-camera sets (development sets: seeds 1217-1226). Every call of OpenCV's ECC
in ``VariationModel.fitted_warp`` is recorded as ``zmaps`` makes it. Run from the repository's root; prints
shift_rule.txt's lines. Arguments NAME=SET:SPLIT ... read those sets instead (plan-2.md)."""
import sys

import cv2
import numpy as np
import torch

import model.draem.variation as variation
from model.draem.checkpoint import load_checkpoint
from model.draem.variation import MAX_SHIFT
from station.datasets import load_split

SETS = (("square, validation", "data/line-pv-val", "val"),
        ("square, seed 1194", "data/line-panel-heldout-1194", "test"),
        ("square, seed 1222", "data/look-built-1222", "test"), ("turned 3", "data/turned3-1217", "test"),
        ("turned 4", "data/turned4-1218", "test"), ("turned 8", "data/turned8-1219", "test"),
        ("turned 12", "data/turned12-1221", "test"), ("turned 20", "data/turned20-1225", "test"),
        ("turned 30", "data/turned30-1226", "test"))
if len(sys.argv) > 1:
    SETS = tuple((a.split("=")[0], *a.split("=")[1].split(":")) for a in sys.argv[1:])
det = load_checkpoint("model/weights/default").detector
cfg, var = det.config, det.variation
h, w = cfg.input_shape
calls: list[np.ndarray | None] = []
ecc = cv2.findTransformECC


def recorded(*args, **kwargs):
    try:
        out = ecc(*args, **kwargs)
    except cv2.error:
        calls.append(None)
        raise
    calls.append(out[1].copy())
    return out


def plausible_scale(m: np.ndarray) -> bool:
    sx, sy = float(np.hypot(*m[:, 0])), float(np.hypot(*m[:, 1]))
    return bool(np.isfinite(m).all()) and 0.8 <= sx <= 1.25 and 0.8 <= sy <= 1.25


variation.cv2.findTransformECC = recorded
centre = np.array([(w - 1) / 2, (h - 1) / 2, 1.0], np.float32)
for name, path, split in SETS:
    sp = load_split(path, split, cfg.priors, cfg.input_shape, roi=cfg.roi, frame_aspect=cfg.frame_aspect,
                    dome_segments=cfg.dome_segments, around_px=cfg.around_px, progress=False)
    calls.clear()
    with torch.no_grad():
        for i in range(0, len(sp.priors), 32):
            var.zmaps(sp.priors[i:i + 32].float(), around=sp.around[i:i + 32].float())
    failed = sum(m is None for m in calls)
    ok = [m for m in calls if m is not None]
    old = sum(plausible_scale(m) and abs(m[0, 2]) <= MAX_SHIFT * w and abs(m[1, 2]) <= MAX_SHIFT * h for m in ok)
    new = 0
    for m in ok:
        dx, dy = m @ centre - centre[:2]
        new += plausible_scale(m) and abs(dx) <= MAX_SHIFT * w and abs(dy) <= MAX_SHIFT * h
    print(f"{name:20s} {len(calls):3d} warps, {failed} not converged; kept by the old rule {old}, by the new {new}",
          flush=True)
