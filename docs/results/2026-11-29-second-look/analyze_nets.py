"""Section 4's design figures from nets.py's OUT.npz (used sets only): cascades that add a residual network's score
to the shipped second look, thresholds from the good validation parts held fixed; per held-out set and pooled:
caught at 1 % and 5 %, image AUROC, good parts rejected at 1 %, and caught at 1 % per type.
Usage: python analyze_nets.py OUT.npz."""

from __future__ import annotations

import sys

import numpy as np

from model.draem.metrics import auroc, false_reject_threshold
from model.draem.second_look import robust_location_spread

d = np.load(sys.argv[1])
gate = float(d["gate"])
sets = sorted(k[:-7] for k in d.files if k.endswith("_window") and k != "val_window")
nets = [k[4:] for k in d.files if k.startswith("val_") and k[4:] not in ("window", "chi", "label", "type")]


def score(s: str, cand: str) -> np.ndarray:
    """window: no second look; shipped: the larger of window and test above the gate; +NET: the larger of the three
    above the gate; ungated NET: the larger of window and the network for every part; alone NET: the network only.
    NET: the calibrated score (``station residual``'s: mean of the top probabilities, robust SD); NET_logit: the mean
    of the top logits instead, robust SD over the good validation parts (the probabilities saturate at 1); rule48
    NET_logit: rule 48's X (above the gate, the larger of shipped and NET, each over its own validation 1 %
    threshold)."""
    c, t = d[f"{s}_window"], d[f"{s}_chi"]
    if cand == "window":
        return c
    if cand == "shipped":
        return np.where(c > gate, np.maximum(c, t), c)
    net = d[f"{s}_{cand.split()[-1]}"]
    if cand.endswith("_logit"):  # the mean top logits, put in robust SD over the good validation parts
        loc, spread = robust_location_spread(d[f"val_{cand.split()[-1]}"][d["val_label"] == 0])
        net = (net - loc) / spread
    if cand.startswith("rule48"):  # each divided by its own 1 % threshold on the good validation parts
        ts = false_reject_threshold(score("val", "shipped")[d["val_label"] == 0], 0.01)
        tn = false_reject_threshold(score("val", "alone " + cand.split()[-1])[d["val_label"] == 0], 0.01)
        return np.where(c > gate, np.maximum(score(s, "shipped") / ts, net / tn), score(s, "shipped") / ts)
    if cand.startswith("alone"):
        return net
    if cand.startswith("+"):
        return np.where(c > gate, np.maximum(np.maximum(c, t), net), c)
    return np.maximum(c, net)


cands = ["window", "shipped", *(f"{how} {n}" for how in ("+", "ungated", "alone") for n in nets),
         *(f"rule48 {n}" for n in nets if n.endswith("_logit"))]
vg = d["val_label"] == 0
print("| candidate | val 1 % thr | " + " | ".join(f"{s}: 1 % / 5 % / AUROC" for s in sets) +
      " | pooled: 1 % / 5 % / AUROC / good rejected 1 % |")
print("|---" * (len(sets) + 3) + "|")
types = sorted({t for s in sets for t in d[f"{s}_type"] if t})
per_type = {}
for k in cands:
    v = score("val", k)
    t1, t5 = false_reject_threshold(v[vg], 0.01), false_reject_threshold(v[vg], 0.05)
    row, xs, ys, ts = [], [], [], []
    for s in sets:
        x, y = score(s, k), d[f"{s}_label"]
        xs.append(x)
        ys.append(y)
        ts.append(d[f"{s}_type"])
        row.append(f"{np.mean(x[y == 1] > t1):.3f} / {np.mean(x[y == 1] > t5):.3f} / {auroc(y, x):.3f}")
    x, y, ty = np.concatenate(xs), np.concatenate(ys), np.concatenate(ts)
    per_type[k] = [np.mean(x[ty == t] > t1) for t in types]
    print(f"| {k} | {t1:.2f} | " + " | ".join(row) + f" | {np.mean(x[y == 1] > t1):.3f} / "
          f"{np.mean(x[y == 1] > t5):.3f} / {auroc(y, x):.3f} / {np.mean(x[y == 0] > t1):.3f} |")
print("\npooled held-out, caught at 1 % per type:\n| candidate | " + " | ".join(types) + " |")
print("|---" * (len(types) + 1) + "|")
for k in cands:
    print(f"| {k} | " + " | ".join(f"{v:.3f}" for v in per_type[k]) + " |")
