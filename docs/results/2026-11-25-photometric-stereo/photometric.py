"""Rule 18: two frames of each part under the two halves of a dome (rule.md; the page
docs/results/2026-11-25-photometric-stereo.md).

    PYTHONPATH=. OMP_NUM_THREADS=2 .venv/bin/python docs/results/2026-11-25-photometric-stereo/photometric.py OUT.json
        [--four] [--line controlled]

Sets (same seeds, so the same parts, poses, defects, exposure and stray light): data/uniform-{good,heldout} (the
uniform dome), data/gradient-{good,heldout} (bright at +x), data/gradient-minus-{good,heldout} (bright at -x).
Each row is a variation model with the shipped recipe fitted on the good set's 210 train parts, thresholds from its
90 val and test parts, scored on the held-out set's 300 parts (``narrow-lines/compare.py``'s method). ``--four``
(rule 19) adds row E from data/gradient-{90,270}-{good,heldout} (bright at +y and -y) as well. ``--line controlled``
(rule 20): the station-fixed line's sets instead, data/controlled-{uniform,minus,90,270}-{good,heldout} and
data/gradient-controlled-{good,heldout} (bright at +x).
"""
from __future__ import annotations

import copy
import json
import sys
from pathlib import Path

import numpy as np
import torch
from sklearn.metrics import roc_auc_score

from model.draem.checkpoint import load_checkpoint
from model.draem.variation import VariationModel

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "2026-11-25-narrow-lines"))
from compare import SHAPE, TYPES, load, scores  # the narrowed-lines study's loading and scoring, the same method

EPS = 1e-3


def pair(plus: np.ndarray, minus: np.ndarray, *more: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two (or more) frames' priors (N, 4, H, W: I, DoLP, cos 2a, sin 2a) -> (the mean of their Stokes vectors as
    priors, the tilt t = (I+ - I-) / (I+ + I-) (N, H, W) of the first two)."""
    def stokes(x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return x[:, 0], x[:, 0] * x[:, 1] * x[:, 2], x[:, 0] * x[:, 1] * x[:, 3]

    frames = [stokes(x) for x in (plus, minus, *more)]
    (i1, _, _), (i2, _, _) = frames[:2]
    i, s1, s2 = (sum(f[k] for f in frames) / len(frames) for k in range(3))
    length = np.hypot(s1, s2)
    dolp = np.clip(length / np.maximum(i, EPS), 0.0, 1.0)
    c = np.where(length > 0, s1 / np.maximum(length, 1e-12), 1.0)
    s = np.where(length > 0, s2 / np.maximum(length, 1e-12), 0.0)
    tilt = (i1 - i2) / np.maximum(i1 + i2, EPS)
    return np.stack([i, dolp, c, s], 1).astype(np.float32), tilt.astype(np.float32)


def row(s_good: np.ndarray, s: np.ndarray, label: np.ndarray, kind: np.ndarray) -> dict:
    r = {"auroc": float(roc_auc_score(label, s))}
    for rate in (0.01, 0.05):
        thr = np.quantile(s_good, 1 - rate)
        r[f"caught{rate}"] = float((s[label == 1] > thr).mean())
        r[f"fr{rate}"] = float((s[label == 0] > thr).mean())
    for t in TYPES:
        k = (kind == t) | (label == 0)
        r[t] = float(roc_auc_score(label[k], s[k]))
    return r


def paired_gain(label, kind, a, b, t: str | None, n=1000, seed=0) -> tuple[float, float]:
    """Bootstrap (parts resampled) of AUROC(b) - AUROC(a), over one defect type's parts and the good ones."""
    k = (label == 0) | ((kind == t) if t else (label == 1))
    y, a, b = label[k], a[k], b[k]
    rng = np.random.default_rng(seed)
    d = []
    for _ in range(n):
        i = rng.integers(0, len(y), len(y))
        if y[i].min() != y[i].max():
            d.append(roc_auc_score(y[i], b[i]) - roc_auc_score(y[i], a[i]))
    return float(np.mean(d)), float(np.std(d))


def main() -> None:
    out = sys.argv[1]
    torch.set_num_threads(2)
    data = {}
    four = "--four" in sys.argv
    controlled = "controlled" in sys.argv[2:]
    sets = ({"uniform": "controlled-uniform", "plus": "gradient-controlled", "minus": "controlled-minus",
             "up": "controlled-90", "down": "controlled-270"} if controlled else
            {"uniform": "uniform", "plus": "gradient", "minus": "gradient-minus", "up": "gradient-90",
             "down": "gradient-270"})
    for name in ("uniform", "plus", "minus", *(("up", "down") if four else ())):
        good, held = f"data/{sets[name]}-good", f"data/{sets[name]}-heldout"
        data[name] = (load(good, ["train"]), load(good, ["val", "test"]), load(held, ["test"]))
    ref = data["uniform"]
    for name in [n for n in data if n != "uniform"]:  # the same parts: labels, types and object masks agree
        for a, b in zip(data[name], ref, strict=True):
            assert (a[1] == b[1]).all() and (a[2] == b[2]).all(), name
            print(f"{name}: object masks agree on {np.mean(a[3] == b[3]):.4f} of pixels", flush=True)
    label, kind = ref[2][1], ref[2][2]
    print(f"held-out {len(label)} ({int(label.sum())} defective: "
          + ", ".join(f"{t} {int((kind == t).sum())}" for t in TYPES) + ")", flush=True)
    shipped = load_checkpoint("model/weights/default").detector.variation
    inputs = {"A. uniform": [ref[i][0] for i in range(3)]}
    summed, tilts = [], []
    for i in range(3):
        x, t = pair(data["plus"][i][0], data["minus"][i][0])
        summed.append(x)
        tilts.append(t)
    inputs["B. pair, sum"] = summed
    inputs["C. pair, sum + tilt"] = [np.concatenate([x, t[:, None]], 1) for x, t in zip(summed, tilts, strict=True)]
    inputs["D. intensity + tilt"] = [np.stack([x[:, 0], t], 1) for x, t in zip(summed, tilts, strict=True)]
    if four:
        rows_e = []
        for i in range(3):
            x, tx = pair(*(data[n][i][0] for n in ("plus", "minus", "up", "down")))
            ty = pair(data["up"][i][0], data["down"][i][0])[1]
            rows_e.append(np.concatenate([x, tx[:, None], ty[:, None]], 1))
        inputs["E. four frames"] = rows_e
    masks = ref[0][3]
    result, all_scores = {}, {}
    for name, (xt, xg, xh) in inputs.items():
        if xt.shape[1] == 4:
            model = copy.deepcopy(shipped)
        else:
            c = xt.shape[1]
            model = VariationModel(c, SHAPE, intensity=0, dolp=1 if c >= 5 else None, aolp=2 if c >= 5 else None,
                                   box_px=shipped.box_px)
        model.fit(torch.from_numpy(xt), torch.from_numpy(masks))
        s_good, s = scores(model, xg), scores(model, xh)
        all_scores[name] = s
        r = result[name] = row(s_good, s, label, kind)
        if name != "A. uniform":
            for t in (None, "dent", "scratch"):
                r[f"gain_{t or 'all'}"], r[f"gain_{t or 'all'}_se"] = paired_gain(label, kind, all_scores["A. uniform"],
                                                                                  s, t)
        if name == "E. four frames":
            for t in (None, "dent", "scratch"):
                k = f"vs_C_{t or 'all'}"
                r[k], r[k + "_se"] = paired_gain(label, kind, all_scores["C. pair, sum + tilt"], s, t)
            print(f"E against C: all {r['vs_C_all']:+.3f} ({r['vs_C_all_se']:.3f}) dent {r['vs_C_dent']:+.3f} "
                  f"({r['vs_C_dent_se']:.3f}) scratch {r['vs_C_scratch']:+.3f} ({r['vs_C_scratch_se']:.3f})",
                  flush=True)
        print(f"{name:22s} AUROC {r['auroc']:.3f}  at 1 %: {r['caught0.01']:.0%} ({r['fr0.01']:.1%})  at 5 %: "
              f"{r['caught0.05']:.0%} ({r['fr0.05']:.1%})  " + " ".join(f"{t} {r[t]:.3f}" for t in TYPES)
              + ("" if name == "A. uniform" else
                 f"  gain all {r['gain_all']:+.3f} ({r['gain_all_se']:.3f}) dent {r['gain_dent']:+.3f} "
                 f"({r['gain_dent_se']:.3f}) scratch {r['gain_scratch']:+.3f} ({r['gain_scratch_se']:.3f})"),
              flush=True)
    with open(out, "w") as f:
        json.dump(result, f, indent=1)


if __name__ == "__main__":
    main()
