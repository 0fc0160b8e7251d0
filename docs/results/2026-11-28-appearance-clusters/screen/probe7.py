"""Probe 7: how much the validation AUROC of 8 clusters depends on the k-means seed (least-squares coefficients),
hard clusters against soft ones (each cluster weighted by exp(-d^2 / 2 tau^2), tau the median distance of the
training parts to their nearest centre)."""

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
c = np.load("runs/knn/cache.npz")
ut, rt, jt, uv, rv, jv = (c[k] for k in ("ut", "rt", "jt", "uv", "rv", "jv"))
sc = np.load("runs/knn/scores.npz")
y, types = sc["y"], sc["types"]
try:
    co = np.load("runs/knn/lsq.npz")
    lt, lv = co["lt"], co["lv"]
except FileNotFoundError:
    tr = model_split(ck, MODEL, "data/line-panel-train", "train", good_only=True)
    va = model_split(ck, MODEL, "data/line-panel-val", "val")
    lt = np.stack([vm._judged_residual(x)[1] for x in tr.priors.numpy()])
    lv = np.stack([vm._judged_residual(x)[1] for x in va.priors.numpy()])
    np.savez("runs/knn/lsq.npz", lt=lt, lv=lv)
region, part = vm.scored_region(), vm.region.numpy()
sd = lt.std(0) + 1e-6


def stats(members):
    m = rt[members].mean(0)
    n = len(members)
    return m, np.maximum(1.4826 * np.median(np.abs(rt[members] - m), 0) * np.sqrt(n / max(n - 1, 1)), 0.3)


for seed in range(4):
    cen, lab = kmeans(lt / sd, 8, seed=seed)
    full = [stats(np.flatnonzero(lab == k)) for k in range(8)]
    d_tr = ((lt[:, None] / sd - cen[None]) ** 2).sum(2)
    tau = float(np.median(np.sqrt(d_tr.min(1))))
    for soft in (False, True):

        def z_of(r, d, own=None, own_stats=None, soft=soft, full=full, tau=tau):
            if not soft:
                k = int(d.argmin())
                m, s = own_stats if own is not None else full[k]
                return (r - m) / s
            w = np.exp(-(d - d.min()) / (2 * tau**2))
            w /= w.sum()
            ms = [own_stats if (own is not None and k == own) else full[k] for k in range(8)]
            m = sum(w[k] * ms[k][0] for k in range(8))
            s = np.sqrt(sum(w[k] * ms[k][1] ** 2 for k in range(8)))
            return (r - m) / s

        wt = []
        for i in range(len(ut)):
            mem = np.flatnonzero(lab == lab[i])
            wt.append(window(vm, z_of(rt[i], d_tr[i], lab[i], stats(mem[mem != i])), jt[i]))
        wt = np.stack(wt)
        location = np.median(wt, 0)
        spread = cv2.GaussianBlur(np.percentile(wt, WINDOW_QUANTILE, 0) - location, (0, 0), WINDOW_BLUR_PX)
        spread = np.maximum(spread, max(float(np.percentile(spread[part], 5.0)), ABS_NORMAL_SD / vm.box_px))
        d_v = ((lv[:, None] / sd - cen[None]) ** 2).sum(2)
        s = np.array(
            [
                float(
                    np.where(
                        region & jv[i], np.maximum((window(vm, z_of(rv[i], d_v[i]), jv[i]) - location) / spread, 0), 0
                    ).max()
                )
                for i in range(len(uv))
            ]
        )
        print(
            seed,
            "soft" if soft else "hard",
            "auroc",
            round(roc_auc_score(y, s), 3),
            " ".join(
                f"{t[:5]} {roc_auc_score(y[(~y) | (types == t)], s[(~y) | (types == t)]):.3f}"
                for t in sorted(set(types[y]))
            ),
            flush=True,
        )
