"""Rule 50's decision (rule50.md) from nets50.py's OUT.npz over the validation set and the deciding set (h0), with
columns C (the shipped file's network) and X (the candidate's networks, their mean). Each model scores as its file
does: the shipped cascade, and above the gate the larger of it and the network's mean top logits, each over its own
1 % threshold on the good validation parts (screen50.py's ``cascade``). Thresholds from the good validation parts
held fixed; paired bootstrap SEs (1000 resamples) over the deciding set's parts.
Usage: python decide50.py OUT.npz [C_COLUMN X_COLUMN] (default C X)."""

from __future__ import annotations

import sys

import numpy as np

from model.draem.metrics import auroc, false_reject_threshold
from model.draem.second_look import robust_location_spread

d = np.load(sys.argv[1])
cols = dict(zip("CX", sys.argv[2:4] or ("C", "X"), strict=True))
gate = float(d["gate"])
vg = d["val_label"] == 0


def shipped(s: str) -> np.ndarray:
    c, t = d[f"{s}_window"], d[f"{s}_chi"]
    return np.where(c > gate, np.maximum(c, t), c)


def cascade(s: str, col: str) -> np.ndarray:
    loc, spread = robust_location_spread(d[f"val_{col}"][vg])
    net = lambda z: (d[f"{z}_{col}"] - loc) / spread  # noqa: E731
    tc, tn = false_reject_threshold(shipped("val")[vg], 0.01), false_reject_threshold(net("val")[vg], 0.01)
    return np.where(d[f"{s}_window"] > gate, np.maximum(shipped(s) / tc, net(s) / tn), shipped(s) / tc)


val = {k: cascade("val", c) for k, c in cols.items()}
held = {k: cascade("h0", c) for k, c in cols.items()}
lab, types = d["h0_label"], d["h0_type"]
thr = {k: {fr: false_reject_threshold(v[vg], fr) for fr in (0.01, 0.05)} for k, v in val.items()}


def figures(idx: np.ndarray) -> dict[str, float]:
    y, out = lab[idx], {}
    for k, v in held.items():
        v = v[idx]
        out[f"{k} auroc"] = auroc(y, v)
        for fr in (0.01, 0.05):
            out[f"{k} caught {fr}"] = float(np.mean(v[y == 1] > thr[k][fr]))
            out[f"{k} good rejected {fr}"] = float(np.mean(v[y == 0] > thr[k][fr]))
    return out


rng = np.random.default_rng(50)
allidx = np.arange(len(lab))
kinds = sorted(set(types[lab == 1]))
sub = {"all": allidx, **{t: np.flatnonzero((lab == 0) | (types == t)) for t in kinds}}
point = {k: figures(i) for k, i in sub.items()}
boot = {k: [figures(rng.choice(i, len(i))) for _ in range(1000)] for k, i in sub.items()}


def diff(key: str, part: str = "all") -> tuple[float, float]:
    """X - C and its paired bootstrap SE."""
    return (point[part][f"X {key}"] - point[part][f"C {key}"],
            float(np.std([r[f"X {key}"] - r[f"C {key}"] for r in boot[part]])))


print(f"deciding set: {int((lab == 0).sum())} good, {int((lab == 1).sum())} defective; gate {gate:.3f}; "
      f"C = column {cols['C']}, X = column {cols['X']}")
print("| | C | X | X - C (paired SE) |\n|---|---|---|---|")
for key in ("auroc", "caught 0.01", "caught 0.05", "good rejected 0.01", "good rejected 0.05"):
    dx, s = diff(key)
    print(f"| {key} | {point['all'][f'C {key}']:.3f} | {point['all'][f'X {key}']:.3f} | {dx:+.3f} ({s:.3f}) |")
print("\nper type, against all good parts (image AUROC / caught at 1 % / caught at 5 %; X - C at 1 % (SE)):")
print("| type | defective | C | X | X - C at 1 % (SE) |\n|---|---|---|---|---|")
e = True
for t in kinds:
    f, (dx, s) = point[t], diff("caught 0.01", t)
    e &= dx >= -2 * s
    print(f"| {t} | {int(np.sum(types == t))} | " + " | ".join(
        f"{f[f'{k} auroc']:.3f} / {f[f'{k} caught 0.01']:.0%} / {f[f'{k} caught 0.05']:.0%}" for k in "CX")
        + f" | {dx:+.3f} ({s:.3f}) |")
a = diff("caught 0.01")[0] > diff("caught 0.01")[1]
b = diff("auroc")[0] >= -diff("auroc")[1]
c = diff("caught 0.05")[0] >= -diff("caught 0.05")[1]
dd = diff("good rejected 0.01")[0] <= diff("good rejected 0.01")[1]
print(f"\n(a) {a}  (b) {b}  (c) {c}  (d) {dd}  (e) {e}  -> {'taken' if a and b and c and dd and e else 'not taken'}")
