"""The development screen of the median pose (validation set only; nothing held out is read): the good parts of the
threshold's validation set (``data/line-pv-val``, seed 303, the line as built), each view and the frame around it
turned in the image about the view's centre, as in 2026-12-06-turn-check/synthetic_turns.py, put to each model named
on the command line at its own threshold. Prints, per model and turn (+-12, +-20, +-25 and 0), the good parts it
rejects, those by the window alone (neither the shape nor the outline check beyond its threshold), the parts partly
outside what was read, the median turn_deg and the model's turn_centre. Run from the repository's root:
``PYTHONPATH=. python synthetic_turns.py MODEL...``; its output is synthetic_turns.txt."""

import sys

import cv2
import numpy as np
import torch

from model.draem.adapt import image_scores
from model.draem.checkpoint import load_checkpoint
from station.datasets import load_split

TURNS = (0, 12, -12, 20, -20, 25, -25)


def turned(img: np.ndarray, degrees: float, border: int, value: float = 0.0) -> np.ndarray:
    """(C, H, W) turned counter-clockwise as shown by ``degrees`` about its centre."""
    hh, ww = img.shape[1:]
    m = cv2.getRotationMatrix2D(((ww - 1) / 2, (hh - 1) / 2), degrees, 1.0)
    return np.stack([cv2.warpAffine(c, m, (ww, hh), flags=cv2.INTER_LINEAR, borderMode=border, borderValue=value)
                     for c in img])


for path in sys.argv[1:]:
    ck = load_checkpoint(path)
    cfg, variation = ck.detector.config, ck.detector.variation
    sp = load_split("data/line-pv-val", "val", cfg.priors, cfg.input_shape, roi=cfg.roi,
                    frame_aspect=cfg.frame_aspect, dome_segments=cfg.dome_segments, around_px=cfg.around_px,
                    progress=False)
    good = (sp.label == 0).nonzero().flatten()
    x, around = sp.priors[good].float().numpy(), sp.around[good].float().numpy()
    h, w = x.shape[2:]
    a = cfg.around_px
    print(f"{path}: threshold {ck.threshold:.4f}, turn_centre {float(variation.turn_centre):+.2f}", flush=True)
    for part_turn in TURNS:
        image_turn = -part_turn  # cv2's angle is counter-clockwise as shown, turn_deg clockwise
        ar = np.stack([turned(f, image_turn, cv2.BORDER_CONSTANT, np.nan) for f in around])
        view = np.stack([turned(f, image_turn, cv2.BORDER_REPLICATE)[:, a:a + h, a:a + w] for f in around])
        view = np.where(np.isfinite(view), view, np.stack([turned(v, image_turn, cv2.BORDER_REPLICATE) for v in x]))
        xt, at = torch.from_numpy(view.astype(np.float32)), torch.from_numpy(ar.astype(np.float32))
        s = image_scores(ck.detector, xt, around=at)
        z = variation.zmaps(xt, around=at)
        t = z.turn_deg.numpy()
        rej = s > ck.threshold
        alone = rej & (np.abs(z.edge_bend.numpy()) <= 1) & (z.edge_step.numpy() <= 1)
        unseen = int((z.unseen_fraction.numpy() > 0).sum())
        print(f"  parts turned {part_turn:+3d}: {int(rej.sum())} of {len(s)} good parts rejected, "
              f"{int(alone.sum())} by the window alone; {unseen} partly outside what was read; "
              f"turn_deg median {np.nanmedian(t):+.2f}, {np.nanmin(t):+.2f} to {np.nanmax(t):+.2f}", flush=True)
