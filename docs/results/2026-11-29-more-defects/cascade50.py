"""The shipped cascade as the screens of this page score it, from nets50.py's (or topk50.py's) OUT.npz ``d``:
the window score, above the gate the larger of it and the second look's test, and a residual network column's mean
top logits in robust SD over the good validation parts. ``cascade`` is the file's second look with that column as its
network: above the gate, the larger of the shipped score and the network's, each over its own 1 % threshold on the
good validation parts (``ResidualDetector.look``; "none": the shipped score alone)."""

from __future__ import annotations

import numpy as np

from model.draem.metrics import false_reject_threshold
from model.draem.second_look import robust_location_spread


def held_sets(d) -> list[str]:
    """The held-out sets in ``d`` (h0, h1, ...)."""
    return sorted(k[:-7] for k in d.files if k.endswith("_window") and k != "val_window")


def good_val(d) -> np.ndarray:
    return d["val_label"] == 0


def shipped(d, s: str) -> np.ndarray:
    """Set ``s``'s shipped score without a network (robust SD of the window)."""
    c, t = d[f"{s}_window"], d[f"{s}_chi"]
    return np.where(c > float(d["gate"]), np.maximum(c, t), c)


def findings(d, s: str, col: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Set ``s``'s shipped score and the network column's, each over its own 1 % threshold on the good validation
    parts, and whether each part is above the gate."""
    vg = good_val(d)
    loc, spread = robust_location_spread(d[f"val_{col}"][vg])
    net = lambda z: (d[f"{z}_{col}"] - loc) / spread  # noqa: E731
    tc = false_reject_threshold(shipped(d, "val")[vg], 0.01)
    tn = false_reject_threshold(net("val")[vg], 0.01)
    return shipped(d, s) / tc, net(s) / tn, d[f"{s}_window"] > float(d["gate"])


def cascade(d, s: str, col: str) -> np.ndarray:
    """Set ``s``'s score with network column ``col`` as the second look's network ("none": without one)."""
    if col == "none":
        return shipped(d, s)
    a, b, above = findings(d, s, col)
    return np.where(above, np.maximum(a, b), a)
