"""Shared by the screens: the shipped model's variation model on the validation set, and one line of figures.

Run from the repository root with PYTHONPATH=. (thresholds are set on the same validation parts they score: a
screen, not a result)."""

from __future__ import annotations

import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import auroc, false_reject_threshold
from station.evaluation import model_split

MODEL, VAL = "model/weights/default", "data/line-panel-val"


def load_val():
    """(variation model, (N, C, H, W) priors, (N,) labels, (N,) defect types, (N,) dataset indices)."""
    ck = load_checkpoint(MODEL)
    sp = model_split(ck, MODEL, VAL, "val")
    return (ck.detector.variation, sp.priors.float(), sp.label.numpy(), np.array([t or "" for t in sp.defect_type]),
            np.array(sp.index))


def scores(vm, x) -> tuple[np.ndarray, np.ndarray]:
    """(image scores, share of the part hidden as highlight) of every frame."""
    outs = [vm.zmaps(x[i:i + 50]) for i in range(0, len(x), 50)]
    return (np.concatenate([o.scores.numpy() for o in outs]),
            np.concatenate([o.highlight_fraction.numpy() for o in outs]))


def report(name: str, s: np.ndarray, lab: np.ndarray, types: np.ndarray) -> str:
    """Image AUROC, caught at 1 % and 5 % of the good parts (thresholds on their own scores), per type."""
    good = lab == 0
    t1, t5 = false_reject_threshold(s[good], 0.01), false_reject_threshold(s[good], 0.05)
    row = [f"{name:24s}", f"AUROC {auroc(lab, s):.3f}", f"@1% {np.mean(s[~good] > t1):.0%}",
           f"@5% {np.mean(s[~good] > t5):.0%}"]
    for t in sorted(set(types[~good])):
        sel = good | (types == t)
        row.append(f"{t[:5]} {auroc(lab[sel], s[sel]):.3f}/{np.mean(s[types == t] > t1):.0%}")
    return "  ".join(row)
