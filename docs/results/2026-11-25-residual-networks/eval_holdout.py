"""Rule 2 (d): each type left out of a network's training; that type's validation AUROC against the shipped
statistic's (paired bootstrap SE over that type's defective parts and all good parts); held-out 202 reported too."""

from __future__ import annotations

import json

import numpy as np
from sklearn.metrics import roc_auc_score

from model.draem.metrics import detection_by_type

c = np.load("runs/s32/zcache.npz")
out = {}
for t in ("chip", "dent", "missing_stud", "scratch", "stain"):
    try:
        net = json.load(open(f"runs/s32/net-{t}.json"))
    except FileNotFoundError:
        continue
    r = {}
    for split, key in (("val", "val"), ("held", "held")):
        lab, kind, sv = c[f"{split}_label"], c[f"{split}_type"], c[f"{split}_score"]
        nv = np.array(net[key])
        keep = (lab == 0) | (kind == t)
        a, b, lab_t = sv[keep], nv[keep], lab[keep]
        rng = np.random.default_rng(0)
        d = []
        gi, di = np.where(lab_t == 0)[0], np.where(lab_t == 1)[0]
        for _ in range(1000):
            i = np.concatenate([rng.choice(gi, len(gi)), rng.choice(di, len(di))])
            d.append(roc_auc_score(lab_t[i], b[i]) - roc_auc_score(lab_t[i], a[i]))
        rep = detection_by_type(lab, nv, kind, validation=(c["val_label"], np.array(net["val"])))
        r[split] = {
            "shipped": roc_auc_score(lab_t, a),
            "network": roc_auc_score(lab_t, b),
            "d": float(np.mean(d)),
            "se": float(np.std(d)),
            "caught1": rep.per_type[t].caught[0.01],
            "caught5": rep.per_type[t].caught[0.05],
        }
    out[t] = r
    v = r["val"]
    print(
        f"{t:13s} val shipped {v['shipped']:.3f} net-without-{t} {v['network']:.3f} d {v['d']:+.3f} se {v['se']:.3f} "
        f"pass {v['d'] > -v['se']} caught@1% {v['caught1']:.0%} "
        f"| held {r['held']['shipped']:.3f} vs {r['held']['network']:.3f}"
    )
json.dump(out, open("runs/s32/eval-holdout.json", "w"), indent=1)
