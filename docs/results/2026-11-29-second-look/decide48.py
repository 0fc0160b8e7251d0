"""Rule 48's decision (rule48.md) from design.py's OUT.npz over the validation set and the deciding set (h0): C,
the shipped second look (its ``chi`` statistic), against X, the same cascade with the candidate statistic; both
in robust SD over the good validation parts, thresholds from those parts held fixed, paired bootstrap SEs over the
deciding set's parts. Usage: python decide48.py OUT.npz STATISTIC."""

from __future__ import annotations

import sys

import numpy as np

from model.draem.metrics import auroc, false_reject_threshold
from model.draem.second_look import robust_location_spread

d = np.load(sys.argv[1])
cand = sys.argv[2]
gate = float(d["gate"])
vg = d["val_label"] == 0


def cascade(name: str, key: str) -> np.ndarray:
    loc, spread = robust_location_spread(d[f"val_{key}"][vg])
    c = d[f"{name}_window"]
    t = (np.nan_to_num(d[f"{name}_{key}"], nan=0.0) - loc) / spread
    return np.where(c > gate, np.maximum(c, t), c)


keys = {"C": "chi", "X": cand}
val = {k: cascade("val", s) for k, s in keys.items()}
held = {k: cascade("h0", s) for k, s in keys.items()}
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


allidx = np.arange(len(lab))
point = figures(allidx)
rng = np.random.default_rng(48)
boot = [figures(rng.choice(allidx, len(allidx))) for _ in range(1000)]


def se(key: str) -> float:
    return float(np.std([b[f"X {key}"] - b[f"C {key}"] for b in boot]))


print(f"deciding set: {int((lab == 0).sum())} good, {int((lab == 1).sum())} defective; gate {gate:.3f}; "
      f"X = {cand}; validation 1 % thresholds C {thr['C'][0.01]:.2f}, X {thr['X'][0.01]:.2f}")
print("| | C | X | X - C (paired SE) |\n|---|---|---|---|")
for key in ("auroc", "caught 0.01", "caught 0.05", "good rejected 0.01", "good rejected 0.05"):
    c, x = point[f"C {key}"], point[f"X {key}"]
    print(f"| {key} | {c:.3f} | {x:.3f} | {x - c:+.3f} ({se(key):.3f}) |")
print("\nper type (image AUROC / caught at 1 % / caught at 5 %):\n| type | C | X |\n|---|---|---|")
for t in sorted(set(types[lab == 1])):
    f = figures(np.flatnonzero((lab == 0) | (types == t)))
    print(f"| {t} | " + " | ".join(f"{f[f'{k} auroc']:.3f} / {f[f'{k} caught 0.01']:.0%} / {f[f'{k} caught 0.05']:.0%}"
                                  for k in ("C", "X")) + " |")
a = point["X caught 0.01"] - point["C caught 0.01"] > se("caught 0.01")
b = point["X auroc"] - point["C auroc"] >= -se("auroc")
c = point["X caught 0.05"] - point["C caught 0.05"] >= -se("caught 0.05")
dd = point["X good rejected 0.01"] <= 0.02
print(f"\n(a) {a}  (b) {b}  (c) {c}  (d) {dd}  -> {'taken' if a and b and c and dd else 'not taken'}")
