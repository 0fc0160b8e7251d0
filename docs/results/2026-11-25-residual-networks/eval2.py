"""Second rule (runs/s32/rule.md): candidates from the residual-network ensemble against the shipped statistic on
validation, with paired bootstrap SEs of caught at 1 % / 5 % and AUROC. Usage: eval2.py SEEDTAG... [--held]"""

from __future__ import annotations

import json
import sys

import numpy as np
from sklearn.metrics import roc_auc_score

from model.draem.metrics import detection_by_type, false_reject_threshold

TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")
args = [a for a in sys.argv[1:] if not a.startswith("--")]
c = np.load("runs/s32/zcache.npz")
lv, kv = c["val_label"], c["val_type"]


def zscore(s_val, s):
    g = s_val[lv == 0]
    med = np.median(g)
    return (s - med) / (1.4826 * np.median(np.abs(g - med)) + 1e-9)


def caught(lab, s, rate):
    t = false_reject_threshold(s[lab == 0], rate)
    return float((s[lab == 1] > t).mean())


nets = [json.load(open(f"runs/s32/net-{t}.json")) for t in args]
nv = np.mean([zscore(np.array(n["val"]), np.array(n["val"])) for n in nets], 0)
sv = c["val_score"]
cands = {"shipped": sv, "ensemble": nv, "max": np.maximum(zscore(sv, sv), nv), "sum": zscore(sv, sv) + nv}
rng = np.random.default_rng(0)
gi, di = np.where(lv == 0)[0], np.where(lv == 1)[0]
boots = {k: {"c1": [], "c5": [], "auc": []} for k in cands}
for _ in range(1000):
    i = np.concatenate([rng.choice(gi, len(gi)), rng.choice(di, len(di))])
    for k, s in cands.items():
        boots[k]["c1"].append(caught(lv[i], s[i], 0.01))
        boots[k]["c5"].append(caught(lv[i], s[i], 0.05))
        boots[k]["auc"].append(roc_auc_score(lv[i], s[i]))
out = {}
for k, s in cands.items():
    rep = detection_by_type(lv, s, kv, validation=(lv, s))
    r = {"auroc": rep.overall.image_auroc, "c1": rep.overall.caught[0.01], "c5": rep.overall.caught[0.05]}
    for m in ("c1", "c5", "auc"):
        d = np.array(boots[k][m]) - np.array(boots["shipped"][m])
        r[f"d_{m}"], r[f"se_{m}"] = float(d.mean()), float(d.std())
    r.update({t: rep.per_type[t].image_auroc for t in TYPES})
    r.update({t + "_c1": rep.per_type[t].caught[0.01] for t in TYPES})
    out[k] = r
    print(
        f"{k:9s} val AUROC {r['auroc']:.3f} (d {r['d_auc']:+.3f} se {r['se_auc']:.3f}) @1% {r['c1']:.0%} "
        f"(d {r['d_c1']:+.3f} se {r['se_c1']:.3f}) @5% {r['c5']:.0%} (d {r['d_c5']:+.3f} se {r['se_c5']:.3f}) "
        + " ".join(f"{t[:5]} {r[t]:.3f}/{r[t + '_c1']:.0%}" for t in TYPES)
    )
json.dump(out, open("runs/s32/eval2-" + "-".join(args) + ".json", "w"), indent=1)
