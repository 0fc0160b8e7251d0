"""Rule 49's decision (rule49.md: rule 48's with (d) relative to C) from nets.py's OUT.npz over the validation set
and the deciding set (h0). C: the
shipped file (window score; above the gate, the larger of window and test). X: above the gate, the larger of C and
the residual network's score, each divided by its own 1 % threshold on the good validation parts; C so divided
elsewhere. X_nodent: X with the network trained without dents (for (e)). Thresholds from the good validation
parts held fixed; paired bootstrap SEs over the deciding set's parts. Usage: python decide48.py OUT.npz."""

from __future__ import annotations

import sys

import numpy as np

from model.draem.metrics import auroc, false_reject_threshold
from model.draem.second_look import robust_location_spread

d = np.load(sys.argv[1])
gate = float(d["gate"])
vg = d["val_label"] == 0


def shipped(s: str) -> np.ndarray:
    c, t = d[f"{s}_window"], d[f"{s}_chi"]
    return np.where(c > gate, np.maximum(c, t), c)


def network(s: str, net: str) -> np.ndarray:
    """The network's mean top-10 logits in robust SD over the good validation parts."""
    loc, spread = robust_location_spread(d[f"val_{net}_logit"][vg])
    return (d[f"{s}_{net}_logit"] - loc) / spread


def cascade(s: str, net: str) -> np.ndarray:
    tc = false_reject_threshold(shipped("val")[vg], 0.01)
    tn = false_reject_threshold(network("val", net)[vg], 0.01)
    c = shipped(s) / tc
    return np.where(d[f"{s}_window"] > gate, np.maximum(c, network(s, net) / tn), c)


val = {"C": shipped("val"), "X": cascade("val", "all"), "Xnd": cascade("val", "nodent")}
held = {"C": shipped("h0"), "X": cascade("h0", "all"), "Xnd": cascade("h0", "nodent")}
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
dents = np.flatnonzero((lab == 0) | (types == "dent"))
point, point_d = figures(allidx), figures(dents)
rng = np.random.default_rng(49)
boot = [figures(rng.choice(allidx, len(allidx))) for _ in range(1000)]
boot_d = [figures(rng.choice(dents, len(dents))) for _ in range(1000)]


def se(key: str, x: str = "X", b: list | None = None) -> float:
    return float(np.std([r[f"{x} {key}"] - r[f"C {key}"] for r in (b or boot)]))


print(f"deciding set: {int((lab == 0).sum())} good, {int((lab == 1).sum())} defective; gate {gate:.3f}")
print("| | C | X | X - C (paired SE) | X without dents in training | Xnd - C (SE) |\n|---|---|---|---|---|---|")
for key in ("auroc", "caught 0.01", "caught 0.05", "good rejected 0.01", "good rejected 0.05"):
    c, x, xn = point[f"C {key}"], point[f"X {key}"], point[f"Xnd {key}"]
    print(f"| {key} | {c:.3f} | {x:.3f} | {x - c:+.3f} ({se(key):.3f}) | {xn:.3f} | {xn - c:+.3f} "
          f"({se(key, 'Xnd'):.3f}) |")
print("\nper type (image AUROC / caught at 1 % / caught at 5 %):")
print("| type | C | X | X without dents |\n|---|---|---|---|")
for t in sorted(set(types[lab == 1])):
    f = figures(np.flatnonzero((lab == 0) | (types == t)))
    print(f"| {t} | " + " | ".join(f"{f[f'{k} auroc']:.3f} / {f[f'{k} caught 0.01']:.0%} / {f[f'{k} caught 0.05']:.0%}"
                                  for k in ("C", "X", "Xnd")) + " |")
a = point["X caught 0.01"] - point["C caught 0.01"] > se("caught 0.01")
b = point["X auroc"] - point["C auroc"] >= -se("auroc")
c = point["X caught 0.05"] - point["C caught 0.05"] >= -se("caught 0.05")
dd = point["X good rejected 0.01"] - point["C good rejected 0.01"] <= se("good rejected 0.01")
e = point_d["Xnd caught 0.01"] - point_d["C caught 0.01"] >= -se("caught 0.01", "Xnd", boot_d)
print(f"\ndents, the network trained without them: caught at 1 % {point_d['Xnd caught 0.01']:.3f} against C's "
      f"{point_d['C caught 0.01']:.3f} (SE {se('caught 0.01', 'Xnd', boot_d):.3f})")
print(f"(a) {a}  (b) {b}  (c) {c}  (d) {dd}  (e) {e}  -> {'taken' if a and b and c and dd and e else 'not taken'}")
