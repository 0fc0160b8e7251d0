"""Stop 60 screen: line (ridge) responses of the signed residual beside the shipped curvature window.

A scratch is a line 0.5-1 mm wide and 4-15 mm long (sim/defects.py): the Laplacian at sigma 3 (the shipped window)
answers blobs. Statistics, each the largest channel's absolute response to its signed z (as ``zmaps`` computes z:
clusters, noise level; no second look, no networks):
  log3        sigma^2 LoG_3, the shipped window (``model.draem.variation.curvature``);
  hessS       the scale-normalised Hessian's largest |eigenvalue| at sigma S (isotropic: a line or a blob);
  lineSxL     an oriented line filter: sigma^2 times the second derivative across of a Gaussian of sigma S across and
              L along, 8 angles, the largest |response| (integrates a line's signed contrast along its length).
Calibration as log_screen.py of 2026-11-29-curvature: per-pixel median / 95th percentile (blurred) from the even good
parts of the val split (A), each statistic's scores divided by its A 99th percentile (so a max of two is fair),
thresholds at 1 % and 5 % from the odd good parts (B). Selection on the val split only; the used held-out sets are
printed beside it. Usage: python screen.py MODEL VAL OUT.json [HELDOUT...]"""
import json
import sys

import cv2
import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import auroc
from model.draem.variation import NOISE_CAP, WINDOW_BLUR_PX, WINDOW_QUANTILE, curvature
from station.evaluation import model_split

model, val, out, *tests = sys.argv[1:]
ck = load_checkpoint(model)
vm = ck.detector.variation
ANGLES = 8


def line_kernels(s: float, length: float) -> list[np.ndarray]:
    r = int(np.ceil(4 * max(s, length)))
    y, x = np.mgrid[-r:r + 1, -r:r + 1].astype(np.float64)
    ks = []
    for a in np.arange(ANGLES) * np.pi / ANGLES:
        u = x * np.cos(a) + y * np.sin(a)  # across
        v = -x * np.sin(a) + y * np.cos(a)  # along
        g = np.exp(-0.5 * (u / s) ** 2 - 0.5 * (v / length) ** 2)
        g /= g.sum()
        k = (u * u / s**2 - 1.0) * g
        ks.append((k - k.mean()).astype(np.float32))  # zero sum: a flat field gives 0
    return ks


def hessian_max(z: np.ndarray, s: float) -> np.ndarray:
    b = cv2.GaussianBlur(z, (0, 0), s, borderType=cv2.BORDER_REPLICATE)
    dxx = cv2.Sobel(b, cv2.CV_32F, 2, 0, ksize=3)
    dyy = cv2.Sobel(b, cv2.CV_32F, 0, 2, ksize=3)
    dxy = cv2.Sobel(b, cv2.CV_32F, 1, 1, ksize=3) / 4.0
    half = np.sqrt(((dxx - dyy) / 2) ** 2 + dxy**2)
    m = (dxx + dyy) / 2
    return s * s * np.maximum(np.abs(m + half), np.abs(m - half))


LINES = {f"line{s}x{L}": line_kernels(s, L) for s in (1.0, 1.5) for L in (3.0, 5.0)}
HESS = (1.0, 1.5, 2.0)


def stats(x):
    r, coef, judged, _ = vm._judged_residual(x)
    z = vm.used(vm.clustered(r, coef))
    level = vm.noise_level(np.abs(z), judged)
    z = (np.nan_to_num(z / (level if 1.0 < level <= NOISE_CAP else 1.0)) * judged).astype(np.float32)
    o = {"log3": np.max([curvature(zc, 3.0) for zc in z], 0)}
    for s in HESS:
        o[f"hess{s}"] = np.max([hessian_max(zc, s) for zc in z], 0)
    for name, ks in LINES.items():
        o[name] = np.max([np.abs(cv2.filter2D(zc, cv2.CV_32F, k, borderType=cv2.BORDER_REPLICATE))
                          for zc in z for k in ks], 0)
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
            print(f"{data} {i}/{len(s.priors)}", flush=True)
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
    return {k: (np.maximum((maps[k] - loc) / spread, 0) * (region & judged)).reshape(len(judged), -1).max(1)
            for k, (loc, spread) in cal.items()}


vs = scores(vmaps, vj)
norm = {k: np.percentile(v[A], 99) for k, v in vs.items()}
combos = [(k,) for k in vs] + [("log3", k) for k in vs if k != "log3"]


def combined(sc, combo):
    return np.max([sc[k] / norm[k] for k in combo], 0)


def report(name, sc, labels, types, keep):
    rows = {}
    for combo in combos:
        s, sb = combined(sc, combo), combined(vs, combo)[B]
        t1, t5 = np.percentile(sb, 99), np.percentile(sb, 95)
        lab, st, ty = labels[keep], s[keep], types[keep]
        row = {"auroc": auroc(lab, st), "good_rej_1": float((st[lab == 0] > t1).mean()),
               "caught_1": float((st[lab == 1] > t1).mean()), "caught_5": float((st[lab == 1] > t5).mean())}
        for d in sorted(set(ty) - {""}):
            m = (ty == d) | (lab == 0)
            row[d] = [round(auroc(lab[m], st[m]), 3), round(float((st[ty == d] > t1).mean()), 3)]
        rows["+".join(combo)] = row
        print(f"{name:28s} {'+'.join(combo):18s}",
              json.dumps({k: (round(v, 3) if isinstance(v, float) else v) for k, v in row.items()}), flush=True)
    return rows


result = {"val (B good, all defective)": report("val", vs, vl, vt, (vl == 1) | np.isin(np.arange(len(vl)), B))}
for t in tests:
    tm, tj, tl, tt = run(t, "test")
    result[t] = report(t.split("/")[-1], scores(tm, tj), tl, tt, np.ones(len(tl), bool))
json.dump(result, open(out, "w"), indent=1)
