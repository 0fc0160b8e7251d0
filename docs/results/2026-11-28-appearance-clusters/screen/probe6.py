"""Probe 6: clusters on the least-squares coefficients (highlights left out), as the first implementation did,
against the plain projection (probe5)."""

import cv2
import numpy as np
from sklearn.metrics import roc_auc_score

from model.draem.appearance_clusters import kmeans
from model.draem.checkpoint import load_checkpoint
from model.draem.variation import ABS_NORMAL_SD, WINDOW_BLUR_PX, WINDOW_QUANTILE
from station.evaluation import model_split

MODEL = "model/weights/default"


def window(vm, z, judged):
    return vm.window(np.abs(np.nan_to_num(z, nan=0.0, posinf=0.0, neginf=0.0)), judged)[0]


ck = load_checkpoint(MODEL)
vm = ck.detector.variation
tr = model_split(ck, MODEL, "data/line-panel-train", "train", good_only=True)
va = model_split(ck, MODEL, "data/line-panel-val", "val")
c = np.load("runs/knn/cache.npz")
ut, rt, jt, uv, rv, jv = (c[k] for k in ("ut", "rt", "jt", "uv", "rv", "jv"))
sc = np.load("runs/knn/scores.npz")
y, types = sc["y"], sc["types"]
lt = np.stack([vm._judged_residual(x)[1] for x in tr.priors.numpy()])
lv = np.stack([vm._judged_residual(x)[1] for x in va.priors.numpy()])
comps = vm.components.numpy().reshape(10, -1)
pt, pv = ut.reshape(len(ut), -1) @ comps.T, uv.reshape(len(uv), -1) @ comps.T
print(
    "coef agreement (corr per component)", [round(float(np.corrcoef(lt[:, k], pt[:, k])[0, 1]), 3) for k in range(10)]
)
region, part = vm.scored_region(), vm.region.numpy()
for name, ct, cv_ in (("plain", pt, pv), ("lsq", lt, lv)):
    sd = ct.std(0) + 1e-6
    cen, lab = kmeans(ct / sd, 8)

    def stats(members):
        m = rt[members].mean(0)
        n = len(members)
        return m, np.maximum(1.4826 * np.median(np.abs(rt[members] - m), 0) * np.sqrt(n / max(n - 1, 1)), 0.3)

    full = {k: stats(np.flatnonzero(lab == k)) for k in range(8)}
    wt = []
    for i in range(len(ut)):
        mem = np.flatnonzero(lab == lab[i])
        m, s = stats(mem[mem != i])
        wt.append(window(vm, (rt[i] - m) / s, jt[i]))
    wt = np.stack(wt)
    location = np.median(wt, 0)
    spread = cv2.GaussianBlur(np.percentile(wt, WINDOW_QUANTILE, 0) - location, (0, 0), WINDOW_BLUR_PX)
    spread = np.maximum(spread, max(float(np.percentile(spread[part], 5.0)), ABS_NORMAL_SD / vm.box_px))
    pred = ((cv_[:, None] / sd - cen[None]) ** 2).sum(2).argmin(1)
    s = np.array(
        [
            float(
                np.where(
                    region & jv[i],
                    np.maximum(
                        (window(vm, (rv[i] - full[pred[i]][0]) / full[pred[i]][1], jv[i]) - location) / spread, 0
                    ),
                    0,
                ).max()
            )
            for i in range(len(uv))
        ]
    )
    print(
        name,
        np.bincount(lab),
        "auroc",
        round(roc_auc_score(y, s), 3),
        " ".join(
            f"{t[:5]} {roc_auc_score(y[(~y) | (types == t)], s[(~y) | (types == t)]):.3f}"
            for t in sorted(set(types[y]))
        ),
        flush=True,
    )
