"""Rule 47's decision from rule 45's `propose_fit.py` scores: C (the shipped window score), X (the cascade of
rule.md: the larger of the window score and the propose-and-test score, each in robust SD over the validation good
parts, for parts above the window's validation 5 % threshold only) and, reported beside it, rule 45's X (the
larger for every part). Validation figures use in-sample thresholds; the held-out set's use validation thresholds
held fixed, with paired bootstrap SEs. Usage: python decide.py SCORES.npz [HELDOUT_NAME] (default heldout0)."""

from __future__ import annotations

import sys

import numpy as np

from model.draem.metrics import auroc, false_reject_threshold

d = np.load(sys.argv[1])
held = sys.argv[2] if len(sys.argv) > 2 else "heldout0"
vgood = d["val_label"] == 0


def robust(s: np.ndarray, ref: np.ndarray) -> np.ndarray:
    med = np.median(ref)
    return (s - med) / (1.4826 * np.median(np.abs(ref - med)) + 1e-9)


G5 = false_reject_threshold(robust(d["val_box"], d["val_box"][vgood])[vgood], 0.05)


def scores(name: str) -> dict[str, np.ndarray]:
    """C: the shipped file's scores; X: the cascade; X45: rule 45's larger of the two for every part."""
    c = robust(d[f"{name}_box"], d["val_box"][vgood])
    t = robust(d[f"{name}_test"], d["val_test"][vgood])
    both = np.maximum(c, t)
    return {"C": d[f"{name}_shipped"], "X": np.where(c > G5, both, c), "X45": both}


val, hs = scores("val"), scores(held)
lab, types = d[f"{held}_label"], d[f"{held}_type"]
thr = {k: {fr: false_reject_threshold(v[vgood], fr) for fr in (0.01, 0.05)} for k, v in val.items()}


def figures(s: dict[str, np.ndarray], idx: np.ndarray) -> dict[str, float]:
    y = lab[idx]
    out = {}
    for k, v in s.items():
        v = v[idx]
        out[f"{k} auroc"] = auroc(y, v)
        for fr in (0.01, 0.05):
            out[f"{k} caught {fr}"] = float(np.mean(v[y == 1] > thr[k][fr]))
            out[f"{k} good rejected {fr}"] = float(np.mean(v[y == 0] > thr[k][fr]))
    return out


allidx = np.arange(len(lab))
point = figures(hs, allidx)
rng = np.random.default_rng(47)
boot = [figures(hs, rng.choice(allidx, len(allidx))) for _ in range(1000)]


def se(key_x: str, key_c: str) -> float:
    return float(np.std([b[key_x] - b[key_c] for b in boot]))


print(f"held-out {held}: {int((lab == 0).sum())} good, {int((lab == 1).sum())} defective; gate g5 = {G5:.3f}")
print("| | C | X | X - C (paired SE) | rule 45's X | X45 - C (SE) |\n|---|---|---|---|---|---|")
for key in ("auroc", "caught 0.01", "caught 0.05", "good rejected 0.01", "good rejected 0.05"):
    c, x, x45 = point[f"C {key}"], point[f"X {key}"], point[f"X45 {key}"]
    print(f"| {key} | {c:.3f} | {x:.3f} | {x - c:+.3f} ({se(f'X {key}', f'C {key}'):.3f}) | {x45:.3f} | "
          f"{x45 - c:+.3f} ({se(f'X45 {key}', f'C {key}'):.3f}) |")
print("\nper type (image AUROC / caught at 1 % / caught at 5 %):\n| type | C | X | rule 45's X |\n|---|---|---|---|")
for t in sorted(set(types[lab == 1])):
    f = figures(hs, np.flatnonzero((lab == 0) | (types == t)))
    print(f"| {t} | " + " | ".join(f"{f[f'{k} auroc']:.3f} / {f[f'{k} caught 0.01']:.0%} / {f[f'{k} caught 0.05']:.0%}"
                                  for k in ("C", "X", "X45")) + " |")
a = point["X caught 0.01"] - point["C caught 0.01"] > se("X caught 0.01", "C caught 0.01")
b = point["X auroc"] - point["C auroc"] >= -se("X auroc", "C auroc")
c = point["X caught 0.05"] - point["C caught 0.05"] >= -se("X caught 0.05", "C caught 0.05")
dd = point["X good rejected 0.01"] <= 0.02
print(f"\n(a) {a}  (b) {b}  (c) {c}  (d) {dd}  -> {'taken' if a and b and c and dd else 'not taken'}")
vl = d["val_label"]
for k, v in val.items():
    t1, t5 = thr[k][0.01], thr[k][0.05]
    print(f"validation (in-sample thresholds) {k}: AUROC {auroc(vl, v):.3f}, caught at 1 % "
          f"{np.mean(v[vl == 1] > t1):.1%}, at 5 % {np.mean(v[vl == 1] > t5):.1%}")
