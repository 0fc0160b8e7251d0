"""Validation screen: the variation model's per-place spread re-measured on the calibration set's good parts.

Reads runs/a64/w-pf.npz (calibration, data/line-pf-val) and w-pv.npz (screen, data/line-pv-val) from windows.py.
Usage (repository root): python docs/results/2026-11-30-place-tail/tail.py
"""

import cv2
import numpy as np


def load(name: str) -> dict:
    d = np.load(f"runs/a64/w-{name}.npz")
    return {k: d[k] for k in d}


def image_scores(d: dict, score_map) -> np.ndarray:
    """Each part's largest per-place score over its judged pixels (as zmaps scores a part)."""
    z = np.maximum(score_map(d["w"].astype(np.float32)), 0) * d["judged"]
    return z.reshape(len(z), -1).max(1)


def caught(s: np.ndarray, lab: np.ndarray, typ: np.ndarray, rate: float) -> dict:
    """Share of defective parts (in all and per type) above the rate's point on the good parts."""
    t = np.quantile(s[lab == 0], 1 - rate, method="higher")
    out = {"all": float((s[lab == 1] > t).mean())}
    for ty in sorted(set(typ[lab == 1])):
        out[ty] = float((s[(lab == 1) & (typ == ty)] > t).mean())
    return out


def auroc(s: np.ndarray, lab: np.ndarray) -> float:
    p, n = s[lab == 1], s[lab == 0]
    return float(((p[:, None] > n[None]) + 0.5 * (p[:, None] == n[None])).mean())


def blur(a: np.ndarray, sigma: float) -> np.ndarray:
    return cv2.GaussianBlur(a.astype(np.float32), (0, 0), sigma)


def paired_se(a: np.ndarray, b: np.ndarray, lab: np.ndarray, rate: float, n: int = 1000) -> float:
    """Bootstrap SE (good and defective parts resampled apart) of caught-at-rate(b) - caught-at-rate(a)."""
    rng = np.random.default_rng(0)
    g, d = np.where(lab == 0)[0], np.where(lab == 1)[0]
    out = []
    for _ in range(n):
        gi, di = rng.choice(g, len(g)), rng.choice(d, len(d))
        t = [np.quantile(s[gi], 1 - rate, method="higher") for s in (a, b)]
        out.append((b[di] > t[1]).mean() - (a[di] > t[0]).mean())
    return float(np.std(out))


pf, pv = load("pf"), load("pv")
loc, spread = pf["loc"], pf["spread"]
good = pf["label"] == 0
cal, calj = pf["w"][good].astype(np.float32), pf["judged"][good]
print(f"calibration good parts {len(cal)}; screen: {int((pv['label'] == 0).sum())} good, "
      f"{int(pv['label'].sum())} defective")
variants = {"shipped": lambda w: (w - loc) / spread}
for q in (95, 99):
    qq = np.nanpercentile(np.where(calj, cal, np.nan), q, axis=0)
    qq = np.nan_to_num(qq, nan=float(np.nanmedian(qq)))
    for sigma in (2.0, 4.0):
        for floor in (0.5, 1.0):
            sp = np.maximum(blur(qq - loc, sigma), spread * floor)
            variants[f"q{q} blur{sigma} (floor {floor}x)"] = lambda w, sp=sp: (w - loc) / sp
u = loc + spread  # an exponential tail above the shipped spread's point: mean excess per place, pooled by a blur
for sigma in (2.0, 4.0, 8.0):
    over = calj & (cal > u)
    beta = blur(np.where(over, cal - u, 0).sum(0), sigma) / np.maximum(blur(over.sum(0), sigma), 1e-3)
    beta = np.maximum(beta, np.percentile(beta, 5))
    variants[f"exp tail blur{sigma}"] = lambda w, beta=beta: np.where(w > u, 1 + (w - u) / beta, (w - loc) / spread)

scored = {}
for name, f in variants.items():
    s = scored[name] = image_scores(pv, f)
    c1, c5 = caught(s, pv["label"], pv["dtype"], 0.01), caught(s, pv["label"], pv["dtype"], 0.05)
    print(f"{name:26s} AUROC {auroc(s, pv['label']):.3f} @1%: {c1['all']:.3f} "
          + " ".join(f"{k[:5]}={c1[k]:.2f}" for k in c1 if k != "all") + f" | @5%: {c5['all']:.3f}")
best = "q99 blur2.0 (floor 1.0x)"
se1, se5 = (paired_se(scored["shipped"], scored[best], pv["label"], r) for r in (0.01, 0.05))
print(f"{best} - shipped, caught: paired bootstrap SE {se1:.3f} at 1 %, {se5:.3f} at 5 %")
