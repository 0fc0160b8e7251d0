"""Screen: how the look's members are joined, from dump.py's per-member top logits: each draw alone, their mean (a
`--members 3` look), their median and their minimum (a finding the members agree on). Each joined look calibrated
as `station residual` does (calibration set's good parts), blended and thresholded as `station blend` and `station
threshold` do (validation set's good parts, 1 %). Prints good parts rejected and defective caught at that threshold
on every dumped set, and caught at matched rates. Usage: aggregate.py DUMP_DIR MODEL"""

import sys
from pathlib import Path

import numpy as np
import torch

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import false_reject_threshold as frt
from model.draem.residual import blended
from model.draem.second_look import robust_location_spread

dump, model = Path(sys.argv[1]), sys.argv[2]
det = load_checkpoint(model).detector
look = det.variation.second_look
weight = float(det.residual.blend[0])
sets = {p.stem: dict(np.load(p)) for p in sorted(dump.glob("*.npz"))}
JOINS = {"m0": lambda lg: lg[:, 0], "m1": lambda lg: lg[:, 1], "m2": lambda lg: lg[:, 2],
         "mean": lambda lg: lg.mean(1), "median": lambda lg: np.median(lg, 1), "min": lambda lg: lg.min(1),
         "m0+m1": lambda lg: lg[:, [0, 1]].mean(1), "m0+m2": lambda lg: lg[:, [0, 2]].mean(1),
         "m1+m2": lambda lg: lg[:, [1, 2]].mean(1)}


def scores_of(join, cal):
    loc, spread, t, tv, t_w, t_f = cal
    out = {}
    for name, s in sets.items():
        found = look.from_window_sd((JOINS[join](s["logits"]) - loc) / spread / t * tv)
        b = blended(torch.from_numpy(s["score"]), torch.from_numpy(s["window"]), torch.from_numpy(found), weight,
                    t_w, t_f).numpy()
        out[name] = np.where(s["unjudged"], np.inf, b)
    return out


def calibrate(join):
    c, v = sets["calib"], sets["val"]
    g = c["label"] == 0
    lg = JOINS[join](c["logits"][g])
    loc, spread = robust_location_spread(lg)
    t = frt((lg - loc) / spread, 0.01)
    tv = frt(look.window_sd(c["score"][g]), 0.01)
    gv = v["label"] == 0
    found = look.from_window_sd((JOINS[join](v["logits"][gv]) - loc) / spread / t * tv)
    return loc, spread, t, tv, frt(v["score"][gv], 0.01), frt(found, 0.01)


rows = []
for join in JOINS:
    sc = scores_of(join, calibrate(join))
    thr = frt(sc["val"][sets["val"]["label"] == 0], 0.01)
    line = [f"{join:6s}"]
    for name in sets:
        if name == "calib":
            continue
        s = sc[name]
        lab = sets[name]["label"]
        g, d = lab == 0, lab == 1
        rate = [f"{name} {int((s[g] > thr).sum())}/{int(g.sum())}"]
        if d.any() and name != "vallens":
            rate.append(f"{(s[d] > thr).mean() * 100:.1f}%")
            m = []
            for k in (1, 2, 5):
                q = np.sort(s[g])[::-1][int(np.floor(g.sum() * k / 100))]
                m.append((s[d] > q).mean() * 100)
            rate.append(f"[{np.mean(m):.1f}]")
        line.append(" ".join(rate))
    print("  ".join(line))
