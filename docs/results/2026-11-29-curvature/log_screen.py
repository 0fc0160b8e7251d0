"""Stop 59 screen: the variation model's window statistic (box mean of the largest channel's |z|, 5 px) against a
Laplacian of Gaussian of each channel's signed z (largest |response|, scale-normalised by sigma^2): a dent tilts the
surface, so its residual is a curvature, opposite across it, that a box of |z| averages with the noise around it.

For a model file's variation model, as ``zmaps`` computes z (clusters, noise level; no second look, no residual
network). Per-pixel location/spread (as the fit's ``_position``) from the even-numbered good parts of the val split
(A); each statistic's scores divided by its A 99th percentile (so that a max over statistics is fair); thresholds at
1 % and 5 % from the odd-numbered good parts (B). Selection on the val split (B good parts against its defective
parts); then each held-out set, thresholds held."""
import json
import sys

import cv2
import numpy as np
from scipy.ndimage import gaussian_filter

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import auroc
from model.draem.variation import NOISE_CAP, WINDOW_BLUR_PX, WINDOW_QUANTILE
from station.evaluation import model_split

model, val, out, *tests = sys.argv[1:]
ck = load_checkpoint(model)
vm = ck.detector.variation
SIGMAS = (1.5, 2.0, 2.5, 3.0, 4.0)


def stats(x):
    r, coef, judged, _ = vm._judged_residual(x)
    z = vm.used(vm.clustered(r, coef))
    level = vm.noise_level(np.abs(z), judged)
    z = np.nan_to_num(z / (level if 1.0 < level <= NOISE_CAP else 1.0)) * judged
    o = {"abs5": cv2.blur(np.abs(z).max(0), (5, 5), borderType=cv2.BORDER_REPLICATE)}
    for s in SIGMAS:
        o[f"log{s}"] = s * s * np.max([np.abs(gaussian_filter(zc, s, order=(2, 0)) +
                                              gaussian_filter(zc, s, order=(0, 2))) for zc in z], 0)
    return o, judged


def run(data, split):
    s = model_split(ck, model, data, split)
    maps, judged = {}, []
    for x in s.priors.numpy():
        o, j = stats(x)
        judged.append(j)
        for k, v in o.items():
            maps.setdefault(k, []).append(v.astype(np.float32))
    return {k: np.stack(v) for k, v in maps.items()}, np.stack(judged), np.asarray(s.label), np.array(s.defect_type)


region = vm.scored_region()
vmaps, vj, vl, vt = run(val, "val")
good = np.flatnonzero(vl == 0)
A, B = good[0::2], good[1::2]
cal = {}
for k, w in vmaps.items():
    loc = np.median(w[A], 0)
    spread = cv2.GaussianBlur(np.percentile(w[A], WINDOW_QUANTILE, 0) - loc, (0, 0), WINDOW_BLUR_PX)
    cal[k] = (loc, np.maximum(spread, max(float(np.percentile(spread[region], 5.0)), 1e-3)))


def scores(maps, judged):
    out = {}
    for k, (loc, spread) in cal.items():
        z = np.maximum((maps[k] - loc) / spread, 0) * (region & judged)
        out[k] = z.reshape(len(z), -1).max(1)
    return out


vs = scores(vmaps, vj)
norm = {k: np.percentile(v[A], 99) for k, v in vs.items()}
combos = [(k,) for k in vs] + [("abs5", f"log{s}") for s in SIGMAS]


def combined(sc, combo):
    return np.max([sc[k] / norm[k] for k in combo], 0)


def report(name, sc, labels, types, keep):
    rows = {}
    for combo in combos:
        s = combined(sc, combo)
        sb = combined(vs, combo)[B]
        t1, t5 = np.percentile(sb, 99), np.percentile(sb, 95)
        lab, st, ty = labels[keep], s[keep], types[keep]
        row = {"auroc": auroc(lab, st), "good_rej_1": float((st[lab == 0] > t1).mean()),
               "caught_1": float((st[lab == 1] > t1).mean()), "caught_5": float((st[lab == 1] > t5).mean())}
        for d in sorted(set(ty) - {""}):
            m = (ty == d) | (lab == 0)
            row[d] = [round(auroc(lab[m], st[m]), 3), round(float((st[ty == d] > t1).mean()), 3)]
        rows["+".join(combo)] = row
        print(f"{name:28s} {'+'.join(combo):12s}",
              json.dumps({k: (round(v, 3) if isinstance(v, float) else v) for k, v in row.items()}), flush=True)
    return rows


result = {"val (B good, all defective)": report("val", vs, vl, vt, (vl == 1) | np.isin(np.arange(len(vl)), B))}
for t in tests:
    tm, tj, tl, tt = run(t, "test")
    result[t] = report(t.split("/")[-1], scores(tm, tj), tl, tt, np.ones(len(tl), bool))
json.dump(result, open(out, "w"), indent=1)
