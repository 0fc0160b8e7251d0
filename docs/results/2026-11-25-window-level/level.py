"""Rule 15 (rule.md): the variation model with a window level per frame against the shipped fit, on validation
(paired bootstrap), on held-out set 202 under every default shift of ``station bench shift`` and the five combinations
of the frame-shifts page (thresholds from
validation: 1 %, 5 % and the shipped rule's F1-max), and on held-out set 212 (paired bootstrap).

Usage: level.py OUT.json, from the repository root (about 10 min on 2 cores)."""

from __future__ import annotations

import copy
import json
import sys

import numpy as np
import torch

sys.path.insert(0, "docs/results/2026-11-25-physical-anomalies")
from bootstrap import compare, held_out

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import choose_threshold, false_reject_threshold
from model.draem.shifts import SHIFTS, Channels, shift
from station.evaluation import model_split

MODEL = "model/weights/default"
COMBINED = (
    "dolp x0.7 & blur 0.5 px",
    "dolp x1.5 & blur 0.5 px",
    "gamma 0.8 & exposure x1.3",
    "dolp x0.5 & rotate 2 deg",
    "dolp x0.7 & gamma 1.25 & blur 0.5 px & zoom x1.02",
)
ck = load_checkpoint(MODEL)
ch = Channels.of(ck.detector.config.priors)
shipped = copy.deepcopy(ck.detector.variation)
tr = model_split(ck, MODEL, "data/line-polar-train", "train", good_only=True)
candidate = copy.deepcopy(shipped)
candidate.fit(tr.priors, tr.object_mask, window_level=True)
fits = {"shipped": shipped, "level": candidate}
print("fitted", flush=True)


def scores(model, priors: np.ndarray) -> np.ndarray:
    t = torch.from_numpy(priors)
    return np.concatenate([model.zmaps(t[i : i + 50]).scores.numpy() for i in range(0, len(t), 50)])


va = model_split(ck, MODEL, "data/line-polar-val", "val")
lv, kv = va.label.numpy(), np.array([t or "" for t in va.defect_type])
val = {k: scores(m, va.priors.numpy()) for k, m in fits.items()}
own = {k: choose_threshold(lv, v, 0.05).threshold for k, v in val.items()}
result: dict = {"validation": compare(lv, kv, val), "own_threshold": own}
ho = model_split(ck, MODEL, "data/line-polar-heldout", "test")
lh, kh = ho.label.numpy(), np.array([t or "" for t in ho.defect_type])
for name in (*SHIFTS, *COMBINED):
    hs = {k: scores(m, shift(name, ho.priors.numpy(), ch)) for k, m in fits.items()}
    result[name] = held_out(lh, kh, hs, lv, val, name)
    for k in hs:
        r = result[name][k]
        r["good_rejected_5"] = float((hs[k][lh == 0] > false_reject_threshold(val[k][lv == 0], 0.05)).mean())
        r["good_rejected_own"] = float((hs[k][lh == 0] > own[k]).mean())
        print(
            f"{name} {k}: good rejected at 1 % {r['good_rejected_1']:.1%}, 5 % {r['good_rejected_5']:.1%}, own "
            f"{r['good_rejected_own']:.1%}",
            flush=True,
        )
h2 = model_split(ck, MODEL, "data/line-polar-heldout-212", "test")
l2, k2 = h2.label.numpy(), np.array([t or "" for t in h2.defect_type])
result["212 paired"] = compare(l2, k2, {k: scores(m, h2.priors.numpy()) for k, m in fits.items()})
cells = [n for n in (*SHIFTS, *COMBINED)]
worst = {
    "auroc_drop": max(result[n]["shipped"]["auroc"] - result[n]["level"]["auroc"] for n in cells),
    **{
        f"rise_{t}": max(
            result[n]["level"][f"good_rejected_{t}"] - result[n]["shipped"][f"good_rejected_{t}"] for n in cells
        )
        for t in ("1", "5", "own")
    },
}
result["rule 15 (b)"] = worst
print(worst, flush=True)
json.dump(result, open(sys.argv[1], "w"), indent=1)
