"""Rule 16: the variation model's three channels whitened at each place (rule.md; the page
docs/results/2026-11-25-channels-and-pooling.md).

    PYTHONPATH=. OMP_NUM_THREADS=2 .venv/bin/python docs/results/2026-11-25-channels-and-pooling/whiten.py \
        data/line-polar-train data/line-polar-val data/line-polar-heldout data/line-polar-heldout-212 OUT.json

Refits the shipped variation model on TRAIN's good train parts (as `station variation` does); its fit returns the
training parts' left-out signed residuals (after the noise level), ``zmaps(signed=True)`` every scored part's. From
those maps each statistic (the shipped one recomputed, and the two whitened ones) is computed with the shipped box,
per-place calibration and maximum. Validation thresholds (1 %, 5 %, best F1) are held fixed on the held-out sets;
set 202 is also scored under every default shift of `station bench shift`.
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
from model.draem.metrics import detection_by_type, f1_max, false_reject_threshold
from model.draem.shifts import SHIFTS, Channels, shift
from model.draem.variation import ABS_NORMAL_SD, WINDOW_BLUR_PX, WINDOW_QUANTILE, VariationModel
from station.datasets import load_split

PRIORS = ("intensity", "dolp", "aolp")
SHAPE = (96, 192)
TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")
BOX = 5
SHRINK, RIDGE = 0.1, 0.01
STATISTICS = ("shipped", "whitened rms", "whitened max")


def load(root: str, split: str, good_only: bool = False):
    s = load_split(root, split, PRIORS, SHAPE, roi="band", progress=False, good_only=good_only)
    return s.priors.float(), s.label.numpy(), np.array([t or "" for t in s.defect_type]), s.object_mask


def whitening(signed: np.ndarray) -> np.ndarray:
    """(N, 3, H, W) good parts' signed residuals -> (H, W, 3, 3) inverse square root of their covariance at each
    pixel, shrunk toward its diagonal (rule.md)."""
    cov = np.einsum("nchw,ndhw->hwcd", signed, signed, optimize=True) / len(signed)
    diag = np.einsum("hwcc->hwc", cov)
    cov = (1 - SHRINK) * cov + SHRINK * np.eye(3) * diag[..., None] + RIDGE * np.eye(3)
    val, vec = np.linalg.eigh(cov)
    return np.einsum("hwij,hwj,hwkj->hwik", vec, 1.0 / np.sqrt(val), vec).astype(np.float32)


def pixel_map(s: np.ndarray, white: np.ndarray, statistic: str) -> np.ndarray:
    """(3, H, W) signed residual -> (H, W) per-pixel statistic before the box."""
    if statistic == "shipped":
        return np.abs(s).max(0)
    w = np.einsum("hwcd,dhw->chw", white, s, optimize=True)
    return np.sqrt((w ** 2).mean(0)) if statistic == "whitened rms" else np.abs(w).max(0)


def windows(signed: np.ndarray, white: np.ndarray, statistic: str) -> np.ndarray:
    return np.stack([cv2.blur(pixel_map(s, white, statistic), (BOX, BOX), borderType=cv2.BORDER_REPLICATE)
                     for s in signed])


class Statistic:
    """One statistic's per-place calibration from the training windows, as ``VariationModel.fit``."""

    def __init__(self, name: str, train: np.ndarray, white: np.ndarray, region: np.ndarray) -> None:
        self.name, self.white = name, white
        w = windows(train, white, name)
        self.loc = np.median(w, 0)
        spread = cv2.GaussianBlur(np.percentile(w, WINDOW_QUANTILE, 0) - self.loc, (0, 0), WINDOW_BLUR_PX)
        self.spread = np.maximum(spread, max(float(np.percentile(spread[region], 5.0)), ABS_NORMAL_SD / BOX))

    def scores(self, signed: np.ndarray, judged: np.ndarray, eroded: np.ndarray) -> np.ndarray:
        w = windows(signed, self.white, self.name)
        m = np.maximum((w - self.loc) / self.spread, 0.0) * (judged & eroded)
        return m.reshape(len(m), -1).max(1)


def signed_maps(model: VariationModel, x: torch.Tensor) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Scored parts -> (their used channels' signed maps (N, 3, H, W), judged (N, H, W), zmaps' scores)."""
    s, j, z = [], [], []
    for i in range(0, len(x), 50):
        out = model.zmaps(x[i:i + 50], signed=True)
        s.append(np.delete(out.signed.numpy(), model.dolp, axis=1))
        j.append(out.judged.numpy())
        z.append(out.scores.numpy())
    return np.concatenate(s), np.concatenate(j), np.concatenate(z)


def bootstrap_auroc(lab, a, b, n=1000, seed=0) -> tuple[float, float]:
    rng = np.random.default_rng(seed)
    d = []
    for _ in range(n):
        i = rng.integers(0, len(lab), len(lab))
        if lab[i].min() == lab[i].max():
            continue
        d.append(roc_auc_score(lab[i], b[i]) - roc_auc_score(lab[i], a[i]))
    return float(np.mean(d)), float(np.std(d))


def report(s_val, lab_val, s, lab, kind) -> dict:
    rep = detection_by_type(lab, s, kind, validation=(lab_val, s_val))
    r = {"auroc": rep.overall.image_auroc}
    for rate in (0.01, 0.05):
        r[f"caught{rate}"], r[f"fr{rate}"] = rep.overall.caught[rate], rep.false_reject_observed[rate]
    r.update({t: rep.per_type[t].image_auroc for t in TYPES if t in rep.per_type})
    return r


def rejected(s_val, lab_val, s_good) -> dict:
    """Share of good parts rejected at the validation thresholds: 1 %, 5 %, best F1."""
    good = s_val[lab_val == 0]
    t = {"fr0.01": false_reject_threshold(good, 0.01), "fr0.05": false_reject_threshold(good, 0.05),
         "fr_own": f1_max(lab_val, s_val)[1]}
    return {k: float((s_good > v).mean()) for k, v in t.items()}


def main() -> None:
    train_dir, val_dir, heldout_dir, heldout2_dir, out = sys.argv[1:6]
    torch.set_num_threads(2)
    xt, _, _, mt = load(train_dir, "train", good_only=True)
    shipped = load_checkpoint("model/weights/default").detector.variation
    model = copy.deepcopy(shipped)
    train = np.delete(model.fit(xt, mt), model.dolp, axis=1)
    del xt
    region = model.region.numpy()
    eroded = model.scored_region()
    white = whitening(train)
    stats = {name: Statistic(name, train, white, region) for name in STATISTICS}
    print(f"fit {len(train)} parts; whitening's eigenvalues' range over the region: "
          f"{np.percentile(np.linalg.eigvalsh(np.linalg.inv(white[region] @ white[region])), [1, 50, 99], 0)}",
          flush=True)
    del train
    xv, lv, kv, _ = load(val_dir, "val")
    sv_maps, jv, zv = signed_maps(model, xv)
    val = {n: st.scores(sv_maps, jv, eroded) for n, st in stats.items()}
    print("check: shipped statistic recomputed vs zmaps on validation: "
          f"max |diff| {np.abs(val['shipped'] - zv).max():.3g}"
          f" (median score {np.median(zv):.2f}); AUROC {roc_auc_score(lv, zv):.4f} vs "
          f"{roc_auc_score(lv, val['shipped']):.4f}", flush=True)
    result: dict = {"val": {}, "set 212": {}, "set 202 shifts": {}}
    for n in STATISTICS:
        r = report(val[n], lv, val[n], lv, kv)
        r["gain"], r["gain_se"] = bootstrap_auroc(lv, val["shipped"], val[n])
        result["val"][n] = r
        print(f"val {n:13s} AUROC {r['auroc']:.4f} (gain {r['gain']:+.4f} se {r['gain_se']:.4f}) "
              f"1 % {r['caught0.01']:.1%} 5 % {r['caught0.05']:.1%} "
              + " ".join(f"{t[:5]} {r[t]:.3f}" for t in TYPES), flush=True)
    del sv_maps, xv
    for tag, root in (("set 212", heldout2_dir),):
        xh, lh, kh, _ = load(root, "test")
        sh, jh, _ = signed_maps(model, xh)
        held = {n: st.scores(sh, jh, eroded) for n, st in stats.items()}
        for n in STATISTICS:
            r = report(val[n], lv, held[n], lh, kh)
            r["gain"], r["gain_se"] = bootstrap_auroc(lh, held["shipped"], held[n])
            result[tag][n] = r
            print(f"{tag} {n:13s} AUROC {r['auroc']:.4f} (gain {r['gain']:+.4f} se {r['gain_se']:.4f}) "
                  f"1 % {r['caught0.01']:.1%} ({r['fr0.01']:.1%}) 5 % {r['caught0.05']:.1%} ({r['fr0.05']:.1%}) "
                  + " ".join(f"{t[:5]} {r[t]:.3f}" for t in TYPES), flush=True)
        del xh, sh
    xh, lh, kh, _ = load(heldout_dir, "test")
    ch = Channels.of(PRIORS)
    for name in SHIFTS:
        xs = torch.from_numpy(shift(name, xh.numpy(), ch))
        sh, jh, _ = signed_maps(model, xs)
        result["set 202 shifts"][name] = {}
        for n, st in stats.items():
            s = st.scores(sh, jh, eroded)
            r = {"auroc": float(roc_auc_score(lh, s)), **rejected(val[n], lv, s[lh == 0])}
            result["set 202 shifts"][name][n] = r
            print(f"202 {name:13s} {n:13s} AUROC {r['auroc']:.4f} good rejected at 1 % {r['fr0.01']:.1%} "
                  f"5 % {r['fr0.05']:.1%} own {r['fr_own']:.1%}", flush=True)
        with open(out, "w") as f:
            json.dump(result, f, indent=1)


if __name__ == "__main__":
    main()
