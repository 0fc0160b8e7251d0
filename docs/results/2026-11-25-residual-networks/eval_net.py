"""Compare the shipped statistic, the residual network and their calibrated maximum and sum (validation for the
choice, held-out for the report)."""

from __future__ import annotations

import json
import sys

import numpy as np

sys.path.insert(0, "runs/s32")
from sklearn.metrics import roc_auc_score

from model.draem.metrics import detection_by_type

TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")
c = np.load("runs/s32/zcache.npz")
tag = sys.argv[1] if len(sys.argv) > 1 else "all"
net = json.load(open(f"runs/s32/net-{tag}.json"))
lv, kv, lh, kh = c["val_label"], c["val_type"], c["held_label"], c["held_type"]


def cal(sv, s):
    g = sv[lv == 0]
    med = np.median(g)
    mad = 1.4826 * np.median(np.abs(g - med)) + 1e-9
    return (s - med) / mad


def metrics(s_val, s, lab, kind):
    rep = detection_by_type(lab, s, kind, validation=(lv, s_val))
    r = {
        "auroc": rep.overall.image_auroc,
        "c1": rep.overall.caught[0.01],
        "c5": rep.overall.caught[0.05],
        "fr1": rep.false_reject_observed[0.01],
    }
    for t in TYPES:
        r[t] = rep.per_type[t].image_auroc
        r[t + "_c1"] = rep.per_type[t].caught[0.01]
    return r


def boot(lab, a, b, n=1000):
    rng = np.random.default_rng(0)
    d = []
    for _ in range(n):
        i = rng.integers(0, len(lab), len(lab))
        if lab[i].min() != lab[i].max():
            d.append(roc_auc_score(lab[i], b[i]) - roc_auc_score(lab[i], a[i]))
    return np.mean(d), np.std(d)


sv, sh = c["val_score"], c["held_score"]
nv, nh = np.array(net["val"]), np.array(net["held"])
variants = {
    "shipped": (sv, sh),
    "net": (nv, nh),
    "max(shipped, net)": (np.maximum(cal(sv, sv), cal(nv, nv)), np.maximum(cal(sv, sh), cal(nv, nh))),
    "mean(shipped, net)": (cal(sv, sv) + cal(nv, nv), cal(sv, sh) + cal(nv, nh)),
}
res = {}
for name, (a, b) in variants.items():
    rv, rh = metrics(a, a, lv, kv), metrics(a, b, lh, kh)
    g, se = boot(lv, sv, a)
    for tg, r in (("val", rv), ("held", rh)):
        print(
            f"{tag:12s} {name:20s} {tg:4s} AUROC {r['auroc']:.3f} @1% {r['c1']:.0%} ({r['fr1']:.1%}) @5% {r['c5']:.0%} "
            + " ".join(f"{t[:5]} {r[t]:.3f}/{r[t + '_c1']:.0%}" for t in TYPES)
            + (f" gain {g:+.3f} se {se:.3f}" if tg == "val" else "")
        )
    res[name] = {"val": rv, "held": rh, "gain": g, "se": se}
json.dump(res, open(f"runs/s32/eval-{tag}.json", "w"), indent=1)
