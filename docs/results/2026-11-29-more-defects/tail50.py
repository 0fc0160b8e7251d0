"""What the good parts at the top of the shipped file's scores have in common (used sets only): each good part of
the validation set and of held-out seeds 1149-1145 (nets50.py's screen scores, the shipped network as the second
look: ``cascade50.cascade``), against the scene its render drew (params.json): the stray light's azimuth,
elevation and intensity, the part's yaw and place, the camera's azimuth, elevation and distance, the plastic's
roughness, exposure, analog gain and the count of saturated pixels. For each: Spearman's correlation with the
score over all good parts, and the AUROC of the value for the top 3 % of them (0.5: no relation).
Usage: PYTHONPATH=. python tail50.py runs/r50/screen.npz."""

from __future__ import annotations

import json
import math
import sys

import numpy as np
from cascade50 import cascade
from scipy.stats import spearmanr

from model.draem.metrics import auroc
from sim.dataset import open_dataset

SETS = {"val": ("data/line-panel-val", "val"),
        **{f"h{k}": (f"data/line-panel-heldout-{s}", "test") for k, s in enumerate((1149, 1148, 1147, 1146, 1145))}}


def scene(p: dict) -> dict[str, float]:
    """A render's scene draws (degrees, mm, the renderer's units otherwise)."""
    sc = p["scene"]
    light = np.array(sc["light"]["origin"]) - np.array(sc["light"]["target"])
    cam = np.array(sc["camera"]["origin"]) - np.array(sc["camera"]["target"])
    return {"light azimuth": math.degrees(math.atan2(light[1], light[0])),
            "light elevation": math.degrees(math.atan2(light[2], math.hypot(light[0], light[1]))),
            "light intensity": sc["light"]["intensity"], "yaw": math.degrees(sc["pose"]["yaw_rad"]),
            "x (mm)": sc["pose"]["xy_m"][0] * 1e3, "y (mm)": sc["pose"]["xy_m"][1] * 1e3,
            "camera azimuth": math.degrees(math.atan2(cam[1], cam[0])),
            "camera elevation": math.degrees(math.atan2(cam[2], math.hypot(cam[0], cam[1]))),
            "camera distance": float(np.linalg.norm(cam)), "plastic roughness": sc["materials"]["plastic"]["alpha"],
            "exposure": p["sensor"]["exposure_scale"], "analog gain": p["sensor"]["analog_gain"],
            "saturated pixels": p["n_saturated"]}


d = np.load(sys.argv[1])
scores, draws = [], []
for name, (root, split) in SETS.items():
    ds = open_dataset(root)
    idx, lab = ds.indices(split), d[f"{name}_label"]
    assert len(idx) == len(lab), (root, len(idx), len(lab))  # the order nets50.py loaded them in
    for i, y, s in zip(idx, lab, cascade(d, name, "C"), strict=True):
        p = json.loads((ds.root / "samples" / f"{i:06d}" / "params.json").read_text())
        assert p["label"] == y
        if not y:
            scores.append(s)
            draws.append(scene(p))
x = np.array(scores)
top = x >= np.quantile(x, 0.97)
print(f"{len(x)} good parts; top 3 %: {int(top.sum())}\n")
print("| scene draw | Spearman with the score | AUROC for the top 3 % | top 3 % median | others' median |")
print("|---|---|---|---|---|")
for k in draws[0]:
    v = np.array([r[k] for r in draws])
    print(f"| {k} | {spearmanr(v, x).statistic:+.2f} | {auroc(top.astype(int), v):.2f} | {np.median(v[top]):.3g} | "
          f"{np.median(v[~top]):.3g} |")
