"""Rule 9 (rule.md): the variation model fitted on good parts and blurred copies of them, against the shipped fit, on
validation (paired bootstrap, rule 3's comparison) and on held-out set 202 blurred by 1 and 0.75 input px.

Usage: blur.py OUT.json [--max-sigma S] [--confirm] [--library] (default 1.0: rule 9; 1.5: rule 10; 2 --confirm:
rule 11, which adds held-out set 202 blurred by 1.5 px and set 212 unblurred (paired bootstrap) and blurred by 1 px;
1.5 --confirm --library: rule 12, the fit's own copies, ``VariationModel.fit``'s blur_copies_sigma), from the
repository root (about 6 min on 2 cores, 10 with --confirm)."""

from __future__ import annotations

import copy
import json
import sys

import numpy as np
import torch

sys.path.insert(0, "docs/results/2026-11-25-physical-anomalies")
from bootstrap import compare, held_out

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import false_reject_threshold
from model.draem.shifts import Channels, shift
from station.evaluation import model_split

MODEL = "model/weights/default"
ck = load_checkpoint(MODEL)
ch = Channels.of(ck.detector.config.priors)
shipped = copy.deepcopy(ck.detector.variation)
tr = model_split(ck, MODEL, "data/line-polar-train", "train", good_only=True)
x = tr.priors.numpy()
rng = np.random.default_rng(0)
max_sigma = float(sys.argv[sys.argv.index("--max-sigma") + 1]) if "--max-sigma" in sys.argv else 1.0
sigmas = rng.uniform(0.0, max_sigma, len(x))
blurred = np.concatenate(
    [shift(f"blur {s:.4f} px", x[i : i + 1], ch) if s > 0 else x[i : i + 1] for i, s in enumerate(sigmas)]
)
candidate = copy.deepcopy(shipped)
if "--library" in sys.argv:  # rule 12: VariationModel.fit's own copies (the same draws), each left out with its part
    candidate.fit(torch.from_numpy(x), tr.object_mask, blur_copies_sigma=max_sigma)
else:  # rules 9-11: the copies appended as parts of their own
    candidate.fit(torch.from_numpy(np.concatenate([x, blurred])), torch.cat([tr.object_mask, tr.object_mask]))
print(f"fitted on {2 * len(x)} parts", flush=True)


def scores(model, priors: np.ndarray) -> np.ndarray:
    t = torch.from_numpy(priors)
    return np.concatenate([model.zmaps(t[i : i + 50]).scores.numpy() for i in range(0, len(t), 50)])


va = model_split(ck, MODEL, "data/line-polar-val", "val")
lv, kv = va.label.numpy(), np.array([t or "" for t in va.defect_type])
val = {"shipped": scores(shipped, va.priors.numpy()), "blur-augmented": scores(candidate, va.priors.numpy())}
result = {"validation": compare(lv, kv, val)}
confirm = "--confirm" in sys.argv
sets = [("", "data/line-polar-heldout", ("none", "blur 0.75 px", "blur 1 px", "blur 1.25 px"))]
if confirm:
    sets = [
        ("", sets[0][1], (*sets[0][2], "blur 1.5 px")),
        ("212 ", "data/line-polar-heldout-212", ("none", "blur 1 px")),
    ]
for prefix, data, shifts in sets:
    ho = model_split(ck, MODEL, data, "test")
    lh, kh = ho.label.numpy(), np.array([t or "" for t in ho.defect_type])
    for shift_name in shifts:
        name = prefix + shift_name
        hx = shift(shift_name, ho.priors.numpy(), ch)
        hs = {k: scores(m, hx) for k, m in (("shipped", shipped), ("blur-augmented", candidate))}
        result[name] = held_out(lh, kh, hs, lv, val, name)
        if confirm and name == "212 none":  # rule 11 (d): paired bootstrap on the set never used for a choice
            result["212 none paired"] = compare(lh, kh, hs)
        for k in hs:
            t5 = false_reject_threshold(val[k][lv == 0], 0.05)
            result[name][k]["good_rejected_5"] = float((hs[k][lh == 0] > t5).mean())
            print(
                f"{name} {k}: good parts rejected at the validation 5 % threshold "
                f"{result[name][k]['good_rejected_5']:.1%}",
                flush=True,
            )
json.dump(result, open(sys.argv[1], "w"), indent=1)
