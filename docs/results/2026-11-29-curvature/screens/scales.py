"""Stop 59 screen: window statistics at more than one size, and of the signed residual (a matched filter), for a
model file's variation model. Per-pixel location/spread (as the fit's ``_position``) from half of the val split's good
parts (A), thresholds from the other half (B), scored on a held-out set's test split. No second look, no residual
network: the window statistic alone, each with the same calibration, so the rows compare."""
import json
import sys

import cv2
import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import auroc
from model.draem.variation import NOISE_CAP, WINDOW_BLUR_PX, WINDOW_QUANTILE
from station.evaluation import model_split

model, val, test, out = sys.argv[1:5]
KIND = sys.argv[5] if len(sys.argv) > 5 else "boxes"
SIGMAS = (1.5, 3.0, 5.0)
ck = load_checkpoint(model)
vm = ck.detector.variation
BOXES = (5, 9, 15)


def stats(x):
    r, coef, judged, _ = vm._judged_residual(x)
    z = vm.used(vm.clustered(r, coef))
    level = vm.noise_level(np.abs(z), judged)
    z = np.nan_to_num(z / (level if 1.0 < level <= NOISE_CAP else 1.0)) * judged
    a = np.abs(z).max(0)
    o = {}
    if KIND == "tilt":  # a dent tilts the surface: a dipole in the Stokes components, opposite across it
        from scipy.ndimage import gaussian_filter
        o["abs5"] = cv2.blur(a, (5, 5), borderType=cv2.BORDER_REPLICATE)
        for s in SIGMAS:
            g = [(gaussian_filter(zc, s, order=(0, 1)), gaussian_filter(zc, s, order=(1, 0))) for zc in z]
            o[f"tilt{s}"] = s * np.sqrt(sum(gx ** 2 + gy ** 2 for gx, gy in g))
            o[f"log{s}"] = s * s * np.max([np.abs(gaussian_filter(zc, s, order=(2, 0)) +
                                                  gaussian_filter(zc, s, order=(0, 2))) for zc in z], 0)
        return o, judged
    for b in BOXES:
        o[f"abs{b}"] = cv2.blur(a, (b, b), borderType=cv2.BORDER_REPLICATE)
        o[f"sgn{b}"] = b * np.max([np.abs(cv2.blur(zc, (b, b), borderType=cv2.BORDER_REPLICATE)) for zc in z], 0)
    return o, judged


def run(data, split):
    s = model_split(ck, model, data, split)
    maps, judged = {}, []
    for i, x in enumerate(s.priors.numpy()):
        o, j = stats(x)
        judged.append(j)
        for k, v in o.items():
            maps.setdefault(k, []).append(v.astype(np.float32))
        if i % 100 == 0:
            print(split, i, flush=True)
    return {k: np.stack(v) for k, v in maps.items()}, np.stack(judged), np.asarray(s.label), list(s.defect_type)


vmaps, vj, vl, _ = run(val, "val")
tmaps, tj, tl, tt = run(test, "test")
region = vm.scored_region()
good = np.flatnonzero(vl == 0)
A, B = good[0::2], good[1::2]
res = {}
norm_v, norm_t = {}, {}
for k in vmaps:
    w = vmaps[k][A]
    loc = np.median(w, 0)
    spread = cv2.GaussianBlur(np.percentile(w, WINDOW_QUANTILE, 0) - loc, (0, 0), WINDOW_BLUR_PX)
    spread = np.maximum(spread, max(float(np.percentile(spread[region], 5.0)), 1e-3))

    def score(maps, judged, loc=loc, spread=spread):
        z = np.maximum((maps - loc) / spread, 0) * (region & judged)
        return z.reshape(len(z), -1).max(1)

    sv, st = score(vmaps[k], vj), score(tmaps[k], tj)
    norm = np.percentile(sv[A], 99)  # a common scale for the max over statistics
    norm_v[k], norm_t[k] = sv / norm, st / norm
    res[k] = (sv, st)


def report(name, sv, st):
    t1, t5 = np.percentile(sv[B], 99), np.percentile(sv[B], 95)
    row = {"auroc": auroc(tl, st), "good_rejected_1": float((st[tl == 0] > t1).mean()),
           "caught_1": float((st[tl == 1] > t1).mean()), "caught_5": float((st[tl == 1] > t5).mean())}
    for d in sorted(set(tt) - {""}):
        m = (np.array(tt) == d) | (tl == 0)
        row[d] = (round(auroc(tl[m], st[m]), 3), round(float((st[np.array(tt) == d] > t1).mean()), 3))
    print(f"{name:22s}", json.dumps({k: (round(v, 3) if isinstance(v, float) else v) for k, v in row.items()}),
          flush=True)
    return row


rows = {k: report(k, *res[k]) for k in res}
combos = (
    (("abs5", "tilt1.5"), ("abs5", "tilt3.0"), ("abs5", "tilt5.0"), ("abs5", "log1.5"), ("abs5", "log3.0"),
     ("abs5", "tilt3.0", "log3.0")) if KIND == "tilt" else
    (("abs5", "abs9", "abs15"), ("abs5", "sgn5"), ("abs5", "sgn9"), ("abs5", "sgn9", "sgn15"),
     ("abs5", "abs9", "sgn9", "sgn15")))
for combo in combos:
    sv = np.max([norm_v[k] for k in combo], 0)
    st = np.max([norm_t[k] for k in combo], 0)
    rows["+".join(combo)] = report("+".join(combo), sv, st)
json.dump(rows, open(out, "w"), indent=1)
