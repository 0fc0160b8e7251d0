"""How much of each part the shipped file's registration takes from outside the frame (``unseen_fraction``), on
square and turned lines, with what the file decides (docs/results/2026-12-05-outside-view.md; the frame check's
limit ``UNSEEN_LIMIT`` is read off the square sets here, development and validation sets only).

Per set: good and defective parts' unseen fraction (how many above 0 and above the limit, the 99th percentile and
the largest), and the file's rejects among good parts, with and without a part over the limit. Run from the
repository's root: ``python outside_view.py SET SPLIT [SET SPLIT ...]``."""

import sys

import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.frame_checks import UNSEEN_LIMIT
from station.evaluation import model_split

MODEL = "model/weights/default"
ck = load_checkpoint(MODEL)
det = ck.detector.eval()
args = sys.argv[1:]
print(f"limit {UNSEEN_LIMIT}")
print("| set | parts | above 0 | above the limit | p99 | largest | good rejected | of them above the limit |\n"
      "|---|---|---|---|---|---|---|---|")
for data, split in zip(args[::2], args[1::2], strict=True):
    sp = model_split(ck, MODEL, data, split)
    x = sp.priors.float()
    label = sp.label.numpy() == 1
    unseen, scores = [], []
    for b in range(0, len(x), 16):
        out = det.predict(x[b:b + 16])
        unseen.append(out.frame_checks["unseen_fraction"].numpy())
        scores.append(out.score.numpy())
    u, s = np.concatenate(unseen), np.concatenate(scores)
    rej = s > ck.threshold
    for name, m in (("good", ~label), ("defective", label)):
        v = u[m]
        extra = (f"{int(rej[m].sum())} | {int((rej & m & (u > UNSEEN_LIMIT)).sum())}" if name == "good"
                 else f"{int(rej[m].sum())} caught | ")
        print(f"| {data} {name} | {int(m.sum())} | {int((v > 0).sum())} | {int((v > UNSEEN_LIMIT).sum())} | "
              f"{np.percentile(v, 99):.4f} | {v.max():.4f} | {extra} |", flush=True)
