"""Per part of a set, what plan.md's decisions are made of, from the shipped file (model/weights/default): its decision
score without the look network (the window with its checks, window units), its window alone (the map's largest
value, in the window's robust SD: the gate's units) and the network's finding on every part (``look_score``, window
units). Writes runs/look-mean/<set>_<split>.npz (label, defect type, those three). Nothing is chosen here.

Usage: python arrays.py DATA:SPLIT ... (run from the repository's root)."""
import sys
from pathlib import Path

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.with_variation import rows
from station.datasets import load_split

OUT = Path("runs/look-mean")


def arrays(path: str, split: str, model: str = "model/weights/default") -> dict[str, np.ndarray]:
    """One set's split through ``model`` (the shipped file unless given; stop 122's
    ../2026-12-07-ggx-train/screen.py reads other files with it)."""
    det = load_checkpoint(model).detector
    cfg, var, res = det.config, det.variation, det.residual
    sp = load_split(path, split, cfg.priors, cfg.input_shape, roi=cfg.roi, frame_aspect=cfg.frame_aspect,
                    dome_segments=cfg.dome_segments, around_px=cfg.around_px, progress=False)
    x = sp.priors.float()
    around = None if sp.around is None else sp.around.float()
    score, window, logits = [], [], []
    with torch.no_grad():
        for i in range(0, len(x), 16):
            v = var.zmaps(x[i:i + 16], signed=True, around=rows(around, i, 16))
            score.append(v.scores.double().numpy())
            window.append(var.second_look.window_sd(v.maps.flatten(1).amax(1).double().numpy()))
            logits.append(res.top_logits(*det.residual_inputs(v.signed, v.judged)).numpy())
    found = var.second_look.from_window_sd(res.look_score(torch.from_numpy(np.concatenate(logits))).numpy())
    return {"label": sp.label.numpy() == 1, "kind": np.array(sp.defect_type, dtype=str),
            "score": np.concatenate(score), "window_sd": np.concatenate(window), "found": found}


if __name__ == "__main__":
    OUT.mkdir(parents=True, exist_ok=True)
    for arg in sys.argv[1:]:
        path, split = arg.split(":")
        np.savez(OUT / f"{Path(path).name}_{split}.npz", **arrays(path, split))
        print("done", arg, flush=True)
