"""plan.md's decisions from arrays.py's per-part arrays: C (the shipped cascade) and D (a weighted mean of the window
and the network in units of their 1 % thresholds, with the checks), each with its 1 % and 5 % thresholds from the
good validation parts. Imported by screen.py and read.py."""
from pathlib import Path

import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import false_reject_threshold

RUNS = Path("runs/look-mean")
WEIGHT = 0.25
"""D's share of the window (plan.md: chosen on the validation set among 0, 0.25, 0.5, 0.75)."""
LOOK = load_checkpoint("model/weights/default").detector.variation.second_look


def load(name: str) -> dict[str, np.ndarray]:
    with np.load(RUNS / f"{name}.npz") as d:
        return {k: d[k] for k in d.files}


VAL = load("line-pv-val_val")
_good = ~VAL["label"]
GATE = false_reject_threshold(VAL["window_sd"][_good], 0.05)  # the cascade's gate (robust SD), as the file's
T_W = false_reject_threshold(VAL["score"][_good], 0.01)
T_F = false_reject_threshold(VAL["found"][_good], 0.01)


def cascade(a: dict[str, np.ndarray], gate: float = GATE) -> np.ndarray:
    """C: above the gate the larger of the window (with checks) and the network's finding."""
    s = a["score"].copy()
    up = a["window_sd"] > gate
    s[up] = np.maximum(s[up], a["found"][up])
    return s


def mean(a: dict[str, np.ndarray], weight: float = WEIGHT) -> np.ndarray:
    """D (weight 0: the network alone with the checks): max(weight w / t_w + (1 - weight) f / t_f, c / t_w)."""
    checks = np.where(a["score"] > LOOK.from_window_sd(a["window_sd"]) + 1e-4, a["score"], 0.0)
    return np.maximum(weight * a["score"] / T_W + (1 - weight) * a["found"] / T_F, checks / T_W)


def larger(a: dict[str, np.ndarray]) -> np.ndarray:
    """The larger of the two on every part (no gate), each over its threshold."""
    return np.maximum(a["score"] / T_W, a["found"] / T_F)


def thresholds(decision) -> tuple[float, float]:
    """A decision's thresholds at 1 % and 5 % of the good validation parts rejected (the file's rule)."""
    s = decision(VAL)[_good]
    return false_reject_threshold(s, 0.01), false_reject_threshold(s, 0.05)
