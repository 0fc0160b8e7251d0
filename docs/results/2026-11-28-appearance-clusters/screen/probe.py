"""Probe: does a local (nearest-neighbour) appearance model beat the global PCA on the validation set?"""

from __future__ import annotations

import sys
import time

import numpy as np
from sklearn.metrics import roc_auc_score

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL = "model/weights/default"


def feats(vm, sp):
    mean, part = vm.mean.numpy(), vm.region.numpy()
    cs, comps = vm.channel_scale.numpy()[:, None, None], vm.components.numpy()
    us, rs, js = [], [], []
    for xi in sp.priors.float().numpy():
        warped, judged = vm._registered(xi, part)
        if vm.aligns_polarization:
            warped[:-1] = vm.align_polarization(warped[:-1], mean, judged if judged.any() else part)
        if judged.sum() < 0.5 * part.sum():
            judged = part
        u = (warped[:-1] - mean) / cs * part
        r = vm._residual(u[None], comps, judged)[0] / vm.scale.numpy()
        us.append(u.astype(np.float32))
        rs.append(r.astype(np.float32))
        js.append(judged)
    return np.stack(us), np.stack(rs), np.stack(js)


def stat(vm, z, judged, region):
    z = np.nan_to_num(z, nan=0.0, posinf=0.0, neginf=0.0)
    w, _ = vm.window(np.abs(z), judged)
    return float(np.where(region & judged, w, 0).max())


def main() -> None:
    t0 = time.time()
    ck = load_checkpoint(MODEL)
    vm = ck.detector.variation
    va = model_split(ck, MODEL, "data/line-panel-val", "val")
    print("loaded", time.time() - t0, flush=True)
    c = np.load("runs/knn/cache.npz")
    ut, rt, _jt, uv, rv, jv = (c[k] for k in ("ut", "rt", "jt", "uv", "rv", "jv"))
    y = np.array([d is not None and d != "" for d in va.defect_type])
    types = np.array([d or "good" for d in va.defect_type])
    out = vm.zmaps(va.priors)
    shipped = out.scores.numpy()
    region = vm.scored_region()
    comps = vm.components.numpy().reshape(10, -1)
    ct = ut.reshape(len(ut), -1) @ comps.T
    cv_ = uv.reshape(len(uv), -1) @ comps.T
    sd = ct.std(0) + 1e-6
    res = {"shipped": shipped, "global": np.array([stat(vm, r, j, region) for r, j in zip(rv, jv, strict=False)])}
    for K in (15, 25, 50):
        s_res, s_raw = [], []
        for i in range(len(uv)):
            d = (((ct - cv_[i]) / sd) ** 2).sum(1)
            nb = np.argsort(d)[:K]
            m = rt[nb].mean(0)
            sc = np.maximum(1.4826 * np.median(np.abs(rt[nb] - m), 0) * np.sqrt(K / (K - 1)), 0.3)
            s_res.append(stat(vm, (rv[i] - m) / sc, jv[i], region))
            m2 = ut[nb].mean(0)
            sc2 = 1.4826 * np.median(np.abs(ut[nb] - m2), 0) * np.sqrt(K / (K - 1))
            sc2 = np.maximum(sc2, np.percentile(sc2[:, region], 5, axis=1)[:, None, None])
            s_raw.append(stat(vm, (uv[i] - m2) / sc2, jv[i], region))
        res[f"knn-res{K}"] = np.array(s_res)
        res[f"knn-raw{K}"] = np.array(s_raw)
        print(K, time.time() - t0, flush=True)
    np.savez("runs/knn/scores.npz", y=y, types=types, **res)
    good = ~y
    for name, s in res.items():
        thr = np.quantile(s[good], 0.99)
        line = f"{name:12s} auroc {roc_auc_score(y, s):.3f} caught@1% {np.mean(s[y] > thr):.2f}"
        for t in sorted(set(types[y])):
            sel = good | (types == t)
            line += f" {t[:5]} {roc_auc_score(y[sel], s[sel]):.3f}"
        print(line, flush=True)
    np.savez("runs/knn/scores.npz", y=y, types=types, **res)


if __name__ == "__main__":
    sys.exit(main())
