"""Probe 2: kNN residual with the position calibration (window location/spread from training parts' own kNN windows)."""

from __future__ import annotations

import time

import cv2
import numpy as np
from sklearn.metrics import roc_auc_score

from model.draem.checkpoint import load_checkpoint
from model.draem.variation import ABS_NORMAL_SD, WINDOW_BLUR_PX, WINDOW_QUANTILE

MODEL = "model/weights/default"


def window(vm, z, judged):
    z = np.nan_to_num(z, nan=0.0, posinf=0.0, neginf=0.0)
    return vm.window(np.abs(z), judged)[0]


def main() -> None:
    t0 = time.time()
    ck = load_checkpoint(MODEL)
    vm = ck.detector.variation
    c = np.load("runs/knn/cache.npz")
    ut, rt, jt, uv, rv, jv = (c[k] for k in ("ut", "rt", "jt", "uv", "rv", "jv"))
    sc = np.load("runs/knn/scores.npz")
    y, types = sc["y"], sc["types"]
    region = vm.scored_region()
    part = vm.region.numpy()
    comps = vm.components.numpy().reshape(10, -1)
    ct = ut.reshape(len(ut), -1) @ comps.T
    cv_ = uv.reshape(len(uv), -1) @ comps.T
    sd = ct.std(0) + 1e-6
    loc, spr = vm.window_location.numpy(), vm.window_spread.numpy()
    res = {"shipped": sc["shipped"]}
    res["global+pos"] = np.array(
        [
            float(np.where(region & j, np.maximum((window(vm, r, j) - loc) / spr, 0), 0).max())
            for r, j in zip(rv, jv, strict=True)
        ]
    )
    for K in (25, 50):

        def knn_z(c0, r0, exclude=None, K=K):
            d = (((ct - c0) / sd) ** 2).sum(1)
            if exclude is not None:
                d[exclude] = np.inf
            nb = np.argsort(d)[:K]
            m = rt[nb].mean(0)
            s = np.maximum(1.4826 * np.median(np.abs(rt[nb] - m), 0) * np.sqrt(K / (K - 1)), 0.3)
            return (r0 - m) / s

        wt = np.stack([window(vm, knn_z(ct[i], rt[i], i), jt[i]) for i in range(len(ut))])
        location = np.median(wt, 0)
        spread = cv2.GaussianBlur(np.percentile(wt, WINDOW_QUANTILE, 0) - location, (0, 0), WINDOW_BLUR_PX)
        spread = np.maximum(spread, max(float(np.percentile(spread[part], 5.0)), ABS_NORMAL_SD / vm.box_px))
        s_pos, s_plain = [], []
        for i in range(len(uv)):
            w = window(vm, knn_z(cv_[i], rv[i]), jv[i])
            s_plain.append(float(np.where(region & jv[i], w, 0).max()))
            s_pos.append(float(np.where(region & jv[i], np.maximum((w - location) / spread, 0), 0).max()))
        res[f"knn{K}"] = np.array(s_plain)
        res[f"knn{K}+pos"] = np.array(s_pos)
        print(K, time.time() - t0, flush=True)
    np.savez("runs/knn/scores2.npz", y=y, types=types, **res)
    good = ~y
    for name, s in res.items():
        thr = np.quantile(s[good], 0.99)
        thr5 = np.quantile(s[good], 0.95)
        line = (
            f"{name:12s} auroc {roc_auc_score(y, s):.3f} caught@1% {np.mean(s[y] > thr):.2f} "
            f"@5% {np.mean(s[y] > thr5):.2f}"
        )
        for t in sorted(set(types[y])):
            sel = good | (types == t)
            line += f" {t[:5]} {roc_auc_score(y[sel], s[sel]):.3f}"
        print(line, flush=True)


if __name__ == "__main__":
    main()
