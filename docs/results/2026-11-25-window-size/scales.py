"""The variation model's window size and channel pooling, on cached per-pixel z maps
(docs/results/2026-11-25-window-size.md).

    PYTHONPATH=. .venv/bin/python docs/results/2026-11-25-window-size/scales.py \
        data/line-polar-train data/line-polar-val data/line-polar-heldout OUT.json

Refits the shipped variation model on TRAIN's good train parts (as `station variation` does), records every
per-channel z map its ``window`` sees (the training parts' left-out residuals in the fit, each scored part's in
``zmaps``), then computes each variant's window statistic, per-place calibration and image score from them.
Thresholds at 1 % and 5 % of good parts rejected from VAL's good parts, held fixed on HELDOUT.
"""
from __future__ import annotations

import copy
import json
import sys

import cv2
import numpy as np
import torch
from sklearn.metrics import roc_auc_score

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import detection_by_type
from model.draem.variation import ABS_NORMAL_SD, NOISE_CAP, WINDOW_BLUR_PX, WINDOW_QUANTILE, VariationModel
from station.datasets import load_split

PRIORS = ("intensity", "dolp", "aolp")
SHAPE = (96, 192)
TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")

STASH: list[tuple[np.ndarray, np.ndarray]] = []
_window = VariationModel.window


def spy(self: VariationModel, z: np.ndarray, judged: np.ndarray) -> tuple[np.ndarray, float]:
    STASH.append((self.used(z).astype(np.float16), judged.copy()))
    return _window(self, z, judged)


VariationModel.window = spy  # type: ignore[method-assign]


def load(root: str, split: str, good_only: bool = False):
    s = load_split(root, split, PRIORS, SHAPE, roi="band", progress=False, good_only=good_only)
    return (s.priors.float(), s.label.numpy(), np.array([t or "" for t in s.defect_type]), s.object_mask)


def collect(model: VariationModel, x: torch.Tensor) -> tuple[list, np.ndarray]:
    STASH.clear()
    scores = np.concatenate([model.zmaps(x[i:i + 50]).scores.numpy() for i in range(0, len(x), 50)])
    return list(STASH), scores


def window(z: np.ndarray, judged: np.ndarray, box: int, pool: str) -> np.ndarray:
    z = z.astype(np.float32)
    level = VariationModel.noise_level(z, judged)
    z = z / (level if 1.0 < level <= NOISE_CAP else 1.0)
    if pool.startswith("c"):  # one channel on its own: "c0" intensity, "c1"/"c2" the Stokes components
        m = z[int(pool[1:])]
    else:
        m = z.max(0) if pool == "max" else np.sqrt((z ** 2).mean(0))
    return cv2.blur(m, (box, box), borderType=cv2.BORDER_REPLICATE)


def calibrate(train: list, region: np.ndarray, box: int, pool: str) -> tuple[np.ndarray, np.ndarray]:
    w = np.stack([window(z, j, box, pool) for z, j in train])
    loc = np.median(w, 0)
    spread = cv2.GaussianBlur(np.percentile(w, WINDOW_QUANTILE, 0) - loc, (0, 0), WINDOW_BLUR_PX)
    return loc, np.maximum(spread, max(float(np.percentile(spread[region], 5.0)), ABS_NORMAL_SD / box))


def score(parts: list, scales: list, cal: dict, eroded: np.ndarray) -> np.ndarray:
    out = []
    for z, judged in parts:
        best = 0.0
        for box, pool in scales:
            loc, spread = cal[(box, pool)]
            m = np.maximum((window(z, judged, box, pool) - loc) / spread, 0.0)
            best = max(best, float(m[eroded & judged].max(initial=0.0)))
        out.append(best)
    return np.array(out)


def metrics(s_val, lab_val, s, lab, kind) -> dict:
    """The project's industrial figures (``detection_by_type``: thresholds from the validation scores' good parts,
    held fixed) as this page's JSON keys."""
    rep = detection_by_type(lab, s, kind, validation=(lab_val, s_val))
    r = {"auroc": rep.overall.image_auroc}
    for rate in (0.01, 0.05):
        r[f"caught{rate}"], r[f"fr{rate}"] = rep.overall.caught[rate], rep.false_reject_observed[rate]
        for t in TYPES:
            r[f"{t}_caught{rate}"] = rep.per_type[t].caught[rate]
    r.update({t: rep.per_type[t].image_auroc for t in TYPES})
    return r


def bootstrap_auroc(lab, a, b, n=1000, seed=0) -> tuple[float, float]:
    rng = np.random.default_rng(seed)
    d = []
    for _ in range(n):
        i = rng.integers(0, len(lab), len(lab))
        if lab[i].min() == lab[i].max():
            continue
        d.append(roc_auc_score(lab[i], b[i]) - roc_auc_score(lab[i], a[i]))
    return float(np.mean(d)), float(np.std(d))


VARIANTS = {
    "box 5, max (shipped)": [(5, "max")],
    "box 3": [(3, "max")],
    "box 7": [(7, "max")],
    "box 9": [(9, "max")],
    "box 13": [(13, "max")],
    "box 19": [(19, "max")],
    "box 5, rms": [(5, "rms")],
    "box 9, rms": [(9, "rms")],
    "boxes 5+9": [(5, "max"), (9, "max")],
    "boxes 5+13": [(5, "max"), (13, "max")],
    "boxes 5+9+15": [(5, "max"), (9, "max"), (15, "max")],
    "boxes 3+7+13": [(3, "max"), (7, "max"), (13, "max")],
    "boxes 5+9+15, rms": [(5, "rms"), (9, "rms"), (15, "rms")],
    "box 5, each channel": [(5, "c0"), (5, "c1"), (5, "c2")],
    "boxes 5+9+15, each channel": [(b, f"c{c}") for b in (5, 9, 15) for c in range(3)],
}


def main() -> None:
    train_dir, val_dir, heldout_dir, out = sys.argv[1:5]
    xt, _, _, mt = load(train_dir, "train", good_only=True)
    xv, lv, kv, _ = load(val_dir, "val")
    print(f"fit {len(xt)}, val {len(xv)} ({int(lv.sum())} defective)", flush=True)
    shipped = load_checkpoint("model/weights/default").detector.variation
    fitted = copy.deepcopy(shipped)
    STASH.clear()
    fitted.fit(xt, mt)
    train = list(STASH)
    for name in ("scale", "window_location", "window_spread", "components"):
        a, b = getattr(fitted, name).numpy(), getattr(shipped, name).numpy()
        print(f"refit vs shipped {name}: max |diff| {np.abs(a - b).max():.3g} (of {np.abs(b).max():.3g})")
    val, sv_model = collect(fitted, xv)
    xh, lh, kh, _ = load(heldout_dir, "test")
    print(f"held-out {len(xh)} ({int(lh.sum())} defective)", flush=True)
    held, _sh_model = collect(fitted, xh)
    region = fitted.region.numpy()
    eroded = cv2.erode(region.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
    cal = {}
    for scales in VARIANTS.values():
        for k in scales:
            if k not in cal:
                cal[k] = calibrate(train, region, *k)
    result, base = {}, None
    for name, scales in VARIANTS.items():
        sv, sh = score(val, scales, cal, eroded), score(held, scales, cal, eroded)
        if base is None:
            base = (sv, sh)
            print(f"check: shipped statistic recomputed vs zmaps: max |diff| val {np.abs(sv - sv_model).max():.3g}")
        rv, rh = metrics(sv, lv, sv, lv, kv), metrics(sv, lv, sh, lh, kh)
        rv["gain"], rv["gain_se"] = bootstrap_auroc(lv, base[0], sv)
        result[name] = {"val": rv, "heldout": rh}
    for tag in ("val", "heldout"):
        for name, res in result.items():
            r = res[tag]
            print(f"{name:22s} {tag:4s} AUROC {r['auroc']:.3f} at 1 %: {r['caught0.01']:.0%} ({r['fr0.01']:.1%}) "
                  f"at 5 %: {r['caught0.05']:.0%} ({r['fr0.05']:.1%}) "
                  + " ".join(f"{t[:5]} {r[t]:.3f}/{r[t + '_caught0.01']:.0%}" for t in TYPES)
                  + (f"  gain {r['gain']:+.3f} se {r['gain_se']:.3f}" if tag == "val" else ""), flush=True)
    with open(out, "w") as f:
        json.dump(result, f, indent=1)


if __name__ == "__main__":
    main()
