"""Probe 3: clusters (k-means in the global components' coefficients) instead of per-part neighbours."""

from __future__ import annotations

import time

import cv2
import numpy as np
from sklearn.cluster import KMeans
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
    res = {}
    for M in (6, 8, 12):
        km = KMeans(M, n_init=10, random_state=0).fit(ct / sd)
        lab = km.labels_

        def stats(members):
            m = rt[members].mean(0)
            len(members)
            s = np.ones_like(m)
            return m, s

        full = {k: stats(np.flatnonzero(lab == k)) for k in range(M)}
        wt = []
        for i in range(len(ut)):
            mem = np.flatnonzero(lab == lab[i])
            m, s = stats(mem[mem != i])
            wt.append(window(vm, (rt[i] - m) / s, jt[i]))
        wt = np.stack(wt)
        location = np.median(wt, 0)
        spread = cv2.GaussianBlur(np.percentile(wt, WINDOW_QUANTILE, 0) - location, (0, 0), WINDOW_BLUR_PX)
        spread = np.maximum(spread, max(float(np.percentile(spread[part], 5.0)), ABS_NORMAL_SD / vm.box_px))
        pred = km.predict(cv_ / sd)
        s_pos = []
        for i in range(len(uv)):
            m, s = full[pred[i]]
            w = window(vm, (rv[i] - m) / s, jv[i])
            s_pos.append(float(np.where(region & jv[i], np.maximum((w - location) / spread, 0), 0).max()))
        res[f"km{M}+pos"] = np.array(s_pos)
        print(M, np.bincount(lab), time.time() - t0, flush=True)
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
