"""What the camera's priors show of each defect on this line, for the shipped model: a localised oracle on the held-out
sets, and the share of the defects it separates that the shipped model catches.

Usage: oracle.py OUT.json NAME=DATASET:CACHE ..., from the repository root, after the residual-network study's
cache.py (the CACHE's held_* arrays are that DATASET's test split, in order; the validation threshold comes from
the cache in $ORACLE_VAL_CACHE, default runs/s33/zcache.npz). For each defective part the oracle
knows the defect's pixels (its mask, registered as the model registers the frame, dilated 1 px) and compares a
statistic there with every good part of the same set at the same pixels; a defect above 99 % of them is one a
detector told where to look could catch at 1 % of good parts rejected. Two statistics
(docs/results/2026-11-24-low-rank-variation.md): "pixels", the mean over the pixels of the chi-square over the
channels of the residual z (after the frame's noise level); "mean", the chi-square over the channels of the residual
averaged over the pixels first (pixel noise averaged out). The shipped model's decision on the same parts uses its
validation thresholds (the cache's val_score)."""

from __future__ import annotations

import json
import os
import sys

import cv2
import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import false_reject_threshold
from model.draem.variation import MEDIAN_ABS_NORMAL, NOISE_CAP
from station.datasets import load_split

TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")
model = load_checkpoint("model/weights/default").detector.variation
val = np.load(os.environ.get("ORACLE_VAL_CACHE", "runs/s33/zcache.npz"))  # any cache of the model's validation set
threshold = false_reject_threshold(val["val_score"][val["val_label"] == 0], 0.01)


def level(z: np.ndarray, judged: np.ndarray) -> float:
    s = float(np.median(np.abs(z[:, judged]))) / MEDIAN_ABS_NORMAL if judged.any() else 1.0
    return s if 1.0 < s <= NOISE_CAP else 1.0


def statistics(z: np.ndarray, judged: np.ndarray, masks: np.ndarray) -> np.ndarray:
    """(N parts, M masks, 2): both statistics of every part over every mask's judged pixels."""
    out = np.zeros((len(z), len(masks), 2))
    for i, (zi, ji) in enumerate(zip(z, judged, strict=True)):
        zi = zi.astype(np.float32) / level(zi, ji)
        for k, m in enumerate(masks):
            sel = m & ji
            if sel.any():
                v = zi[:, sel]
                out[i, k] = [(v**2).sum(0).mean(), (v.mean(1) ** 2).sum()]
    return out


result = {}
for arg in sys.argv[2:]:
    name, rest = arg.split("=", 1)
    root, cache = rest.split(":", 1)
    c = np.load(cache)
    s = load_split(root, "test", ("intensity", "dolp", "aolp"), (96, 192), roi="band", progress=False)
    lab, typ = c["held_label"], c["held_type"]
    assert np.array_equal(lab, s.label.numpy()), "the cache is not this set's test split"
    bad = np.where(lab == 1)[0]
    reg = model.register_masks(s.priors[bad].float(), s.defect_mask[bad].bool()).numpy()
    kernel = np.ones((3, 3), np.uint8)
    masks = np.stack([cv2.dilate(m.astype(np.uint8), kernel).astype(bool) for m in reg])
    z, judged = c["held_z"], c["held_judged"]
    good = np.where(lab == 0)[0]
    g = statistics(z[good], judged[good], masks)  # (good, defects, 2)
    d = np.stack([statistics(z[i : i + 1], judged[i : i + 1], masks[k : k + 1])[0, 0] for k, i in enumerate(bad)])
    limit = np.percentile(g, 99, axis=0)  # (defects, 2): 99 % of good parts at each defect's pixels
    seen = d > limit
    caught = c["held_score"][bad] > threshold
    rows = {}
    for t in (*TYPES, "all"):
        sel = np.ones(len(bad), bool) if t == "all" else typ[bad] == t
        either = seen[sel].any(1)
        rows[t] = {
            "defects": int(sel.sum()),
            "oracle_pixels": float(seen[sel, 0].mean()),
            "oracle_mean": float(seen[sel, 1].mean()),
            "oracle_either": float(either.mean()),
            "caught_at_1": float(caught[sel].mean()),
            "caught_of_oracle_either": float(caught[sel][either].mean()) if either.any() else float("nan"),
        }
        r = rows[t]
        print(
            f"{name} {t:13s} n {r['defects']:3d} oracle pixels {r['oracle_pixels']:.0%} mean {r['oracle_mean']:.0%} "
            f"either {r['oracle_either']:.0%}; shipped caught {r['caught_at_1']:.0%}, of those the oracle "
            f"separates {r['caught_of_oracle_either']:.0%}",
            flush=True,
        )
    result[name] = rows
json.dump(result, open(sys.argv[1], "w"), indent=1)
if len(sys.argv) > 2:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(result), figsize=(5 * len(result), 3.2), sharey=True)
    for ax, (name, rows) in zip(np.atleast_1d(axes), result.items(), strict=True):
        x = np.arange(len(rows))
        ax.bar(x - 0.2, [r["oracle_either"] for r in rows.values()], 0.4, label="oracle told where (either statistic)")
        ax.bar(x + 0.2, [r["caught_at_1"] for r in rows.values()], 0.4, label="shipped model")
        ax.set_xticks(x, [t.replace("_", " ") for t in rows], fontsize=8)
        ax.set_title(f"held-out set {name}: separated at 1 % of good parts rejected", fontsize=9)
        ax.set_ylim(0, 1)
    fig.legend(*np.atleast_1d(axes)[0].get_legend_handles_labels(), loc="lower center", ncol=2, fontsize=8)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    fig.savefig(sys.argv[1].replace(".json", ".png"), dpi=110)
