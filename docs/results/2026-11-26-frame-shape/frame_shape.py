"""Rule 22 (rule-22.md): the shipped model on the same parts at two frame shapes. Per part: the variation model's
score, and the registration's scale and shift (cv2.findTransformECC spied as VariationModel.warp_to calls it).

Usage: frame_shape.py OUT.json NAME=DATASET[:SPLIT] ...  (default split test)."""

from __future__ import annotations

import json
import sys

import cv2
import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.datasets import load_split

ECC: list = []
_ecc = cv2.findTransformECC


def spy(*args, **kwargs):
    out = _ecc(*args, **kwargs)
    ECC.append(out[1].copy())
    return out


cv2.findTransformECC = spy
detector = load_checkpoint("model/weights/default").detector
model = detector.variation
result = {}
for arg in sys.argv[2:]:
    name, root = arg.split("=", 1)
    root, split = root.split(":") if ":" in root else (root, "test")
    s = load_split(root, split, ("intensity", "dolp", "aolp"), (96, 192), roi="band", progress=False,
                   frame_aspect=detector.config.frame_aspect)
    scores, scale, shift = [], [], []
    for i in range(len(s.label)):
        ECC.clear()
        out = model.zmaps(s.priors[i: i + 1].float())
        m = ECC[-1]
        scores.append(float(out.scores[0]))
        scale.append(float(np.sqrt(abs(np.linalg.det(m[:, :2])))))
        shift.append([float(m[0, 2]), float(m[1, 2])])
    result[name] = {"label": s.label.tolist(), "type": [t or "" for t in s.defect_type], "score": scores,
                    "scale": scale, "shift": shift}
    sc = np.array(scale)
    print(f"{name}: {len(scores)} parts, registration scale median {np.median(sc):.3f} "
          f"(range {sc.min():.3f}-{sc.max():.3f})", flush=True)
json.dump(result, open(sys.argv[1], "w"))
