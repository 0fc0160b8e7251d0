"""How much of each part the shipped file's registration takes from outside the frame (``unseen_fraction``), on
square and turned lines, with what the file decides (docs/results/2026-12-05-outside-view.md; development and
validation sets only: the report's warning share is read off them).

Per set, good and defective parts: how many had some of the part outside the view (``unseen_fraction`` over
``UNSEEN_LIMIT``), its 99th percentile and largest, the file's rejects and how many of them had some; each good part
rejected with its share. Run from the
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
print("| set | parts | some outside the view | p99 | largest | rejected | of them some outside |\n"
      "|---|---|---|---|---|---|---|")
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
        v, out = u[m], m & (u > UNSEEN_LIMIT)
        print(f"| {data} {name} | {int(m.sum())} | {int(out.sum())} ({100 * out.sum() / m.sum():.1f} %) | "
              f"{np.percentile(v, 99):.4f} | {v.max():.4f} | {int(rej[m].sum())} | {int((rej & out).sum())} |",
              flush=True)
    for i in np.flatnonzero(rej & ~label):
        print(f"  good part {i} rejected: score {s[i]:.4f}, unseen {u[i]:.4f}")
