"""A narrowed line against the shipped model (docs/results/2026-11-25-narrow-lines.md).

    .venv/bin/python docs/results/2026-11-25-narrow-lines/compare.py GOOD HELDOUT OUT.json [--adapt]

GOOD: 300 good parts of the narrowed line (``station render --defects 0``): its train split (210) fits, its val and
test splits (90) set the thresholds at 1 % and 5 % of them rejected. HELDOUT: its held-out parts
(``station render --heldout``). Rows: a variation model fitted on the 210 parts; the shipped model as it is; with
``--adapt``, the shipped model refitted on the first 50, 100 and 210 of them as ``station adapt`` does (reference
and region kept). Each row: image AUROC, caught and good rejected at both thresholds, AUROC per defect type.
"""
from __future__ import annotations

import copy
import json
import sys

import numpy as np
import torch
from sklearn.metrics import roc_auc_score

from model.draem.checkpoint import load_checkpoint
from model.draem.variation import VariationModel
from station.datasets import load_split

PRIORS = ("intensity", "dolp", "aolp")
SHAPE = (96, 192)  # the shipped model's input: the band at 96 px
TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")


def load(root: str, splits: list[str]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    sets = [load_split(root, s, PRIORS, SHAPE, roi="band", progress=False) for s in splits]
    return (np.concatenate([s.priors.numpy() for s in sets]).astype(np.float32),
            np.concatenate([s.label.numpy() for s in sets]),
            np.concatenate([np.array([t or "" for t in s.defect_type]) for s in sets]),
            np.concatenate([s.object_mask.numpy() for s in sets]))


def scores(model: VariationModel, x: np.ndarray) -> np.ndarray:
    return np.concatenate([model.zmaps(torch.from_numpy(x[i:i + 50])).scores.numpy() for i in range(0, len(x), 50)])


def row(model: VariationModel, good: np.ndarray, x: np.ndarray, label: np.ndarray, kind: np.ndarray) -> dict:
    g, s = scores(model, good), scores(model, x)
    r = {"auroc": float(roc_auc_score(label, s))}
    for rate in (0.01, 0.05):
        thr = np.quantile(g, 1 - rate)
        r[f"caught{rate}"] = float((s[label == 1] > thr).mean())
        r[f"fr{rate}"] = float((s[label == 0] > thr).mean())
    for t in TYPES:
        k = (kind == t) | (label == 0)
        r[t] = float(roc_auc_score(label[k], s[k]))
    return r


def main() -> None:
    good_dir, heldout_dir, out = sys.argv[1:4]
    xt, _, _, masks = load(good_dir, ["train"])
    xg, _, _, _ = load(good_dir, ["val", "test"])
    xh, label, kind, _ = load(heldout_dir, ["test"])
    print(f"fit {len(xt)}, thresholds {len(xg)}, held-out {len(xh)} ({int(label.sum())} defective: "
          + ", ".join(f"{t} {int((kind == t).sum())}" for t in TYPES) + ")", flush=True)
    shipped = load_checkpoint("model/weights/default").detector.variation
    fitted = copy.deepcopy(shipped)  # the shipped model's channels and input; every statistic refitted
    fitted.fit(torch.from_numpy(xt), torch.from_numpy(masks))
    models = {f"fit on {len(xt)} of its parts": fitted, "shipped": shipped}
    if "--adapt" in sys.argv:
        for n in (50, 100, len(xt)):
            models[f"shipped adapted on {n}"] = copy.deepcopy(shipped)
            models[f"shipped adapted on {n}"].fit(torch.from_numpy(xt[:n]), keep_reference=True)
    result = {}
    for name, model in models.items():
        r = result[name] = row(model, xg, xh, label, kind)
        print(f"{name:28s} AUROC {r['auroc']:.3f}  at 1 %: {r['caught0.01']:.0%} caught ({r['fr0.01']:.1%} good "
              f"rejected)  at 5 %: {r['caught0.05']:.0%} ({r['fr0.05']:.1%})  "
              + " ".join(f"{t} {r[t]:.3f}" for t in TYPES), flush=True)
    with open(out, "w") as f:
        json.dump(result, f, indent=1)


if __name__ == "__main__":
    main()
