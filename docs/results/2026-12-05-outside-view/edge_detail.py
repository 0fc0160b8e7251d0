"""Per part of a set, beside the shipped file's score: the share of the part outside the view (``unseen_fraction``), the
share of the shape check's edge columns whose searched rows (and one above and below) hold a pixel not seen, and the
shape and outline checks' readings (docs/results/2026-12-05-outside-view.md, Measured). Writes JSON. Run from the
repository's root: ``python edge_detail.py SET SPLIT OUT.json``."""

import json
import sys

from model.draem.checkpoint import load_checkpoint
from model.draem.shape_check import SEARCH_PX
from station.evaluation import model_split

MODEL = "model/weights/default"
ck = load_checkpoint(MODEL)
det = ck.detector.eval()
vm = det.variation
data, split = sys.argv[1:3]
sp = model_split(ck, MODEL, data, split)
x = sp.priors.float()
label = sp.label.numpy() == 1
first, end, row0, slope, sign = (float(v) for v in vm.shape.edge)
rows = []
for b in range(0, len(x), 16):
    out = det.predict(x[b:b+16])
    for j in range(out.score.shape[0]):
        i = b + j
        seen = vm._aligned(x[i].numpy())[3]
        cols = bad = 0
        for col in range(int(first), int(end)):
            line = round(row0 + slope * col)
            lo, hi = max(line - SEARCH_PX, 1), min(line + SEARCH_PX + 1, seen.shape[0] - 1)
            cols += 1
            bad += int((~seen[lo - 1:hi + 2, col]).any())
        rows.append(dict(i=i, label=int(label[i]), score=float(out.score[j]),
                         unseen=float(out.frame_checks["unseen_fraction"][j]), edge_unseen=bad / cols,
                         bend=float(out.frame_checks["edge_bend"][j]), step=float(out.frame_checks["edge_step"][j])))
json.dump(dict(threshold=ck.threshold, rows=rows), open(sys.argv[3], "w"))
