"""How many of a level camera's parts lie partly outside its model's view on a square line: indicative only, from the
small side file of the smoke run (docs/results/2026-12-06-side-drift.md). Run from the repository's root:
``python side_unseen.py MODEL SET SPLIT [SET SPLIT ...]``."""

import sys

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.frame_checks import UNSEEN_LIMIT
from station.evaluation import model_split

model = sys.argv[1]
ck = load_checkpoint(model)
det = ck.detector.eval()
for data, split in zip(sys.argv[2::2], sys.argv[3::2], strict=True):
    sp = model_split(ck, model, data, split)
    x = sp.priors.float()
    with torch.no_grad():
        u = np.concatenate([det.predict(x[b:b + 16]).frame_checks["unseen_fraction"].numpy()
                            for b in range(0, len(x), 16)])
    print(f"{data} {split}: {int((u > UNSEEN_LIMIT).sum())} of {len(u)} parts partly outside the view "
          f"(largest share {u.max():.4f})")
