"""Signed and oriented window statistics on cached signed z maps (runs/s32/zcache.npz)."""

from __future__ import annotations

import json
import sys

import cv2
import numpy as np
from sklearn.metrics import roc_auc_score

from model.draem.metrics import detection_by_type
from model.draem.variation import MEDIAN_ABS_NORMAL, NOISE_CAP, WINDOW_BLUR_PX, WINDOW_QUANTILE

TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")
c = np.load(sys.argv[1])
region = c["region"]
eroded = cv2.erode(region.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)


def level(z, judged):
    s = float(np.median(np.abs(z[:, judged]))) / MEDIAN_ABS_NORMAL if judged.any() else 1.0
    return s if 1.0 < s <= NOISE_CAP else 1.0


def line_kernels(length, width, n=8):
    ks = []
    for i in range(n):
        a = np.pi * i / n
        k = np.zeros((length, length), np.float32)
        h = (length - 1) / 2
        dx, dy = np.cos(a) * h, np.sin(a) * h
        p0 = (round(h * 16 - dx * 16), round(h * 16 - dy * 16))
        p1 = (round(h * 16 + dx * 16), round(h * 16 + dy * 16))
        cv2.line(k, p0, p1, 1.0, width, cv2.LINE_AA, shift=4)
        ks.append(k / k.sum())
    return ks


def stat(z, judged, kind, p):
    z = z.astype(np.float32) / level(z, judged)
    if kind == "abs":  # the shipped statistic
        return cv2.blur(np.abs(z).max(0), (p, p), borderType=cv2.BORDER_REPLICATE)
    if kind == "signed":
        return np.stack([np.abs(cv2.blur(zc, (p, p), borderType=cv2.BORDER_REPLICATE)) for zc in z])
    if kind == "line":
        ks = KERNELS[p]
        return np.stack(
            [np.max([np.abs(cv2.filter2D(zc, -1, k, borderType=cv2.BORDER_REPLICATE)) for k in ks], 0) for zc in z]
        )
    raise ValueError(kind)


KERNELS = {
    (9, 1): line_kernels(9, 1),
    (15, 1): line_kernels(15, 1),
    (15, 3): line_kernels(15, 3),
    (21, 2): line_kernels(21, 2),
}


def maps(zs, judged, kind, p, norm=None):
    out = np.stack([stat(z, j, kind, p) for z, j in zip(zs, judged, strict=True)])
    if out.ndim == 4:  # per channel: standardise each channel globally, then the largest
        if norm is None:
            norm = np.array([np.median(out[:, ch][:, region]) for ch in range(out.shape[1])]) + 1e-6
        out = (out / norm[None, :, None, None]).max(1)
    return out, norm


def calibrate(w):
    loc = np.median(w, 0)
    spread = cv2.GaussianBlur(np.percentile(w, WINDOW_QUANTILE, 0) - loc, (0, 0), WINDOW_BLUR_PX)
    return loc, np.maximum(spread, max(float(np.percentile(spread[region], 5.0)), 1e-3))


def scores(w, judged, cal):
    loc, spread = cal
    pairs = zip(w, judged, strict=True)
    return np.array([float(np.maximum((wi - loc) / spread, 0)[eroded & j].max(initial=0.0)) for wi, j in pairs])


def metrics(s_val, lab_val, s, lab, kind):
    rep = detection_by_type(lab, s, kind, validation=(lab_val, s_val))
    r = {"auroc": rep.overall.image_auroc}
    for rate in (0.01, 0.05):
        r[f"caught{rate}"], r[f"fr{rate}"] = rep.overall.caught[rate], rep.false_reject_observed[rate]
        for t in TYPES:
            r[f"{t}_caught{rate}"] = rep.per_type[t].caught[rate]
    r.update({t: rep.per_type[t].image_auroc for t in TYPES})
    return r


def bootstrap(lab, a, b, n=1000, seed=0):
    rng = np.random.default_rng(seed)
    d = []
    for _ in range(n):
        i = rng.integers(0, len(lab), len(lab))
        if lab[i].min() == lab[i].max():
            continue
        d.append(roc_auc_score(lab[i], b[i]) - roc_auc_score(lab[i], a[i]))
    return float(np.mean(d)), float(np.std(d))


VARIANTS = {
    "box 5 |z| (shipped)": [("abs", 5)],
    "signed box 3": [("signed", 3)],
    "signed box 5": [("signed", 5)],
    "signed box 7": [("signed", 7)],
    "signed box 9": [("signed", 9)],
    "line 9x1": [("line", (9, 1))],
    "line 15x1": [("line", (15, 1))],
    "line 15x3": [("line", (15, 3))],
    "line 21x2": [("line", (21, 2))],
    "shipped + line 15x1": [("abs", 5), ("line", (15, 1))],
    "shipped + signed 5": [("abs", 5), ("signed", 5)],
    "signed 5 + line 15x1": [("signed", 5), ("line", (15, 1))],
}
tj = np.repeat(region[None], len(c["train_z"]), 0)
comp = {}
for parts in VARIANTS.values():
    for k in parts:
        if k in comp:
            continue
        wt, norm = maps(c["train_z"], tj, *k)
        cal = calibrate(wt)
        wv, _ = maps(c["val_z"], c["val_judged"], *k, norm=norm)
        wh, _ = maps(c["held_z"], c["held_judged"], *k, norm=norm)
        comp[k] = (scores(wv, c["val_judged"], cal), scores(wh, c["held_judged"], cal))
        print("computed", k, flush=True)
lv, kv, lh, kh = c["val_label"], c["val_type"], c["held_label"], c["held_type"]
res, base = {}, None
for name, parts in VARIANTS.items():
    sv = np.max([comp[k][0] for k in parts], 0)
    sh = np.max([comp[k][1] for k in parts], 0)
    if base is None:
        base = (sv, sh)
        print("check vs cached shipped scores: val max|diff|", np.abs(sv - c["val_score"]).max())
    rv, rh = metrics(sv, lv, sv, lv, kv), metrics(sv, lv, sh, lh, kh)
    rv["gain"], rv["gain_se"] = bootstrap(lv, base[0], sv)
    res[name] = {"val": rv, "heldout": rh}
for tag in ("val", "heldout"):
    for name, r in res.items():
        r = r[tag]
        print(
            f"{name:22s} {tag:4s} AUROC {r['auroc']:.3f} @1%: {r['caught0.01']:.0%} ({r['fr0.01']:.1%}) "
            f"@5%: {r['caught0.05']:.0%} ({r['fr0.05']:.1%}) "
            + " ".join(f"{t[:5]} {r[t]:.3f}/{r[t + '_caught0.01']:.0%}" for t in TYPES)
            + (f" gain {r['gain']:+.3f} se {r['gain_se']:.3f}" if tag == "val" else ""),
            flush=True,
        )
json.dump(res, open(sys.argv[2], "w"), indent=1)
