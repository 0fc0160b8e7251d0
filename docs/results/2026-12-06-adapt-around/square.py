"""After the reading (not part of the plan's rule): the shipped file on seed 1212's parts seen square
(data/adapt-1212, render-square.sh), the same judged parts as read.py's; which good parts it rejects there, and the
defective parts caught. Run from the repository's root."""

import numpy as np

from model.draem.adapt import image_scores
from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL = "model/weights/default"
ck = load_checkpoint(MODEL)
turned = model_split(ck, MODEL, "data/adapt-1212-turned5", "test")
square = model_split(ck, MODEL, "data/adapt-1212", "test")
assert turned.index == square.index
label = turned.label.numpy() == 1
good = np.flatnonzero(~label)
judged = np.concatenate([good[1::2], np.flatnonzero(label)])  # read.py's judged parts
lab = label[judged]
s = image_scores(ck.detector, square.priors[judged].float(), around=square.around[judged].float())
rej = s > ck.threshold
print(f"square: {int(rej[~lab].sum())} of {int((~lab).sum())} good rejected "
      f"({[int(square.index[judged[i]]) for i in np.flatnonzero(rej & ~lab)]}); {int(rej[lab].sum())} of "
      f"{int(lab.sum())} defective caught ({100 * rej[lab].mean():.1f} %)")
