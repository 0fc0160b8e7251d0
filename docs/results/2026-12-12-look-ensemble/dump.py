"""Screen: per part of a set, what the look's blend reads, each member apart: the variation model's score with its
checks and without the look (window units), its window's largest value, and each member's mean top logits.
Usage: dump.py MODEL SET SPLIT OUT.npz"""

import sys

import numpy as np
import torch

from model.draem.residual import TOP_K
from model.draem.with_variation import rows


def arrays(det, sp) -> dict:
    """``dump.py``'s arrays for detector ``det`` (with its variation model and look) on split ``sp``
    (``station.evaluation.model_split``)."""
    scores, windows, logits = [], [], []
    with torch.no_grad():
        for i in range(0, len(sp.priors), 16):
            v = det.variation.zmaps(sp.priors[i:i + 16], signed=True, around=rows(sp.around, i, 16))
            x, j = det.residual_inputs(v.signed, v.judged)
            j = j.bool() | ~j.flatten(1).any(1).view(-1, 1, 1)
            k = min(TOP_K, j[0].numel())
            logits.append(torch.stack([m(x).masked_fill(~j, -torch.inf).flatten(1).topk(k, 1).values.mean(1)
                                       for m in det.residual.members], 1).double().numpy())
            scores.append(v.scores.double().numpy())
            windows.append(v.maps.flatten(1).amax(1).double().numpy())
    return {"score": np.concatenate(scores), "window": np.concatenate(windows), "logits": np.concatenate(logits),
            "label": sp.label.numpy(), "defect_type": np.array(sp.defect_type), "index": np.array(sp.index),
            "unjudged": np.array([u is not None for u in sp.unjudged]) if sp.unjudged
            else np.zeros(len(sp.label), bool)}


if __name__ == "__main__":
    from model.draem.checkpoint import load_checkpoint
    from station.evaluation import model_split

    model, data, split, out = sys.argv[1:]
    ck = load_checkpoint(model)
    sp = model_split(ck, model, data, split)
    np.savez(out, **arrays(ck.detector, sp))
    print(out, len(sp.label))
