"""top_prior.npy: the share of 200 good training parts (data/line-pf-train) whose pixel is the part's horizontal top
face in the ground truth (normal within ~9 deg of world up, read in the camera's frame), in frame coordinates."""
import json
import os
import sys

import numpy as np

root = sys.argv[1] if len(sys.argv) > 1 else "data/line-pf-train"
acc, n = np.zeros((480, 640)), 0
for name in sorted(os.listdir(f"{root}/samples")):
    p = json.load(open(f"{root}/samples/{name}/params.json"))
    if p["label"] != 0 or p["split"] != "train":
        continue
    g = np.load(f"{root}/samples/{name}/gt.npz")
    acc += g["object_mask"] & (g["normal"][..., 1] > 0.7) & (np.abs(g["normal"][..., 0]) < 0.15)
    n += 1
    if n >= 200:
        break
np.save(os.path.join(os.path.dirname(__file__), "top_prior.npy"), (acc / n).astype(np.float32))
