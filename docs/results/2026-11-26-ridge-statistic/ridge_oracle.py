"""Probe (issue 19, scratches): does subtracting a defect's own surroundings reveal what the shipped statistic and
the localised oracle miss? A localised oracle, as docs/results/2026-11-25-physical-anomalies/oracle.py, with a third
statistic: per channel, the signed residual z averaged over the defect's pixels minus its average over a ring around
them (2-4 px out), chi-square over the channels. A good part's leftovers are smooth over a few pixels, so the ring
takes them out; a scratch's change is local, so it stays.

Usage: ridge_oracle.py CACHE TAG DATASET SPLIT OUT.json  (CACHE from cache.py beside it; TAG val or held)."""

from __future__ import annotations

import json
import sys

import cv2
import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.variation import MEDIAN_ABS_NORMAL, NOISE_CAP
from station.datasets import load_split

TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")
cache, tag, root, split, out = sys.argv[1:6]
model = load_checkpoint("model/weights/default").detector.variation
c = np.load(cache)


def level(z: np.ndarray, judged: np.ndarray) -> float:
    s = float(np.median(np.abs(z[:, judged]))) / MEDIAN_ABS_NORMAL if judged.any() else 1.0
    return s if 1.0 < s <= NOISE_CAP else 1.0


def statistics(z: np.ndarray, judged: np.ndarray, cores: np.ndarray, rings: np.ndarray) -> np.ndarray:
    """(N parts, M masks, 3): pixels, mean and ring statistics of every part over every mask."""
    out = np.zeros((len(z), len(cores), 3))
    for i, (zi, ji) in enumerate(zip(z, judged, strict=True)):
        zi = zi.astype(np.float32) / level(zi, ji)
        for k, (m, r) in enumerate(zip(cores, rings, strict=True)):
            sel, ring = m & ji, r & ji
            if sel.any():
                v = zi[:, sel]
                d = v.mean(1) - (zi[:, ring].mean(1) if ring.any() else 0.0)
                out[i, k] = [(v**2).sum(0).mean(), (v.mean(1) ** 2).sum(), (d**2).sum()]
    return out


s = load_split(root, split, ("intensity", "dolp", "aolp"), (96, 192), roi="band", progress=False)
lab, typ = c[f"{tag}_label"], c[f"{tag}_type"]
assert np.array_equal(lab, s.label.numpy()), "the cache is not this set's split"
bad = np.where(lab == 1)[0]
reg = model.register_masks(s.priors[bad].float(), s.defect_mask[bad].bool()).numpy()
k3, k9 = np.ones((3, 3), np.uint8), np.ones((9, 9), np.uint8)
cores = np.stack([cv2.dilate(m.astype(np.uint8), k3).astype(bool) for m in reg])
rings = np.stack([cv2.dilate(m.astype(np.uint8), k9).astype(bool) for m in reg]) & ~cores
z, judged = c[f"{tag}_z"], c[f"{tag}_judged"]
good = np.where(lab == 0)[0]
g = statistics(z[good], judged[good], cores, rings)
d = np.stack([statistics(z[i: i + 1], judged[i: i + 1], cores[k: k + 1], rings[k: k + 1])[0, 0]
              for k, i in enumerate(bad)])
limit = np.percentile(g, 99, axis=0)
seen = d > limit
rank = (d[None] > g).mean(0)  # per defect: share of good parts below it, per statistic
rows = {}
for t in (*TYPES, "all"):
    sel = np.ones(len(bad), bool) if t == "all" else typ[bad] == t
    rows[t] = {"defects": int(sel.sum()), **{f"oracle_{n}": float(seen[sel, j].mean())
                                             for j, n in enumerate(("pixels", "mean", "ring"))},
               **{f"auroc_{n}": float(rank[sel, j].mean()) for j, n in enumerate(("pixels", "mean", "ring"))}}
    r = rows[t]
    print(f"{t:13s} n {r['defects']:3d} separated at 1 %: pixels {r['oracle_pixels']:.0%} mean {r['oracle_mean']:.0%}"
          f" ring {r['oracle_ring']:.0%}; localised AUROC {r['auroc_pixels']:.3f} / {r['auroc_mean']:.3f} / "
          f"{r['auroc_ring']:.3f}", flush=True)
json.dump(rows, open(out, "w"), indent=1)
