"""Where a file's parts partly outside its view lie (the tall band's page): for each part of a set's split with some
judged pixel the registration took from outside the input, that part's index, how many such pixels, and their
input rows and columns. Usage: python where_unseen.py SET LIMIT [FILE [SPLIT]] (default the shipped file, test)."""

import sys

import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

data, limit = sys.argv[1], int(sys.argv[2])
model = sys.argv[3] if len(sys.argv) > 3 else "model/weights/default"
split = sys.argv[4] if len(sys.argv) > 4 else "test"
ck = load_checkpoint(model)
var = ck.detector.variation
part = var.region.numpy()
sp = model_split(ck, model, data, split, limit=limit)
for i, xi in enumerate(sp.priors.float().numpy()):
    miss = part & ~var._aligned(xi)[3]
    if miss.any():
        ys, xs = np.nonzero(miss)
        print(i, int(miss.sum()), "rows", ys.min(), ys.max(), "cols", xs.min(), xs.max(), flush=True)
