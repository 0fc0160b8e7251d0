"""screen.md: the curvature window at finer scales beside the shipped one (sigma 3), on validation sets only.

Usage: [SIGMAS=1,1.5,2,3] python scale_screen.py MODEL VAL NEWKINDS_VAL OUT.json
SIGMAS (input px): the curvature's scales, each alone and each finer one with the largest (default as screen.md).
Calibration as ../2026-11-29-ridge/window_screen.py (stop 60): per-pixel median / 95th percentile (blurred) of each
statistic from the even good parts of VAL's val split (A), scores over their A 99th percentile, thresholds at 1 % and
5 % from its odd good parts (B); VAL scored on B and its defective parts, NEWKINDS_VAL on its val split."""
import json
import os
import sys

import cv2
import numpy as np
from scipy.ndimage import gaussian_filter

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import auroc
from model.draem.variation import NOISE_CAP, WINDOW_BLUR_PX, WINDOW_QUANTILE
from station.evaluation import model_split

SIGMAS = tuple(float(s) for s in os.environ.get("SIGMAS", "1,1.5,2,3").split(","))
COMBOS = [(f"log{s}",) for s in SIGMAS] + [(f"log{s}", f"log{SIGMAS[-1]}") for s in SIGMAS[:-1]]


def stats(z: np.ndarray) -> dict[str, np.ndarray]:
    return {f"log{s}": s * s * np.max([np.abs(gaussian_filter(zc, s, order=(2, 0)) +
                                              gaussian_filter(zc, s, order=(0, 2))) for zc in z], 0)
            for s in SIGMAS}


def main() -> None:
    model, val, new_val, out = sys.argv[1:]
    ck = load_checkpoint(model)
    vm = ck.detector.variation

    def z_of(x):
        r, coef, judged, _ = vm._judged_residual(x)
        z = vm.used(vm.clustered(r, coef))
        level = vm.noise_level(np.abs(z), judged)
        return (np.nan_to_num(z / (level if 1.0 < level <= NOISE_CAP else 1.0)) * judged).astype(np.float32), judged

    def run(data):
        s = model_split(ck, model, data, "val")
        maps, judged = {}, []
        for i, x in enumerate(s.priors.numpy()):
            z, j = z_of(x)
            judged.append(j)
            for k, v in stats(z).items():
                maps.setdefault(k, []).append(v.astype(np.float32))
            if i % 100 == 0:
                print(f"{data} {i}/{len(s.priors)}", file=sys.stderr, flush=True)
        return {k: np.stack(v) for k, v in maps.items()}, np.stack(judged), np.asarray(s.label), np.array(s.defect_type)

    region = vm.scored_region()
    vmaps, vj, vl, vt = run(val)
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

    def combined(sc, combo):
        return np.max([sc[k] / norm[k] for k in combo], 0)

    def report(name, sc, labels, types, keep):
        rows = {}
        for combo in COMBOS:
            s, sb = combined(sc, combo), combined(vs, combo)[B]
            t1, t5 = np.percentile(sb, 99), np.percentile(sb, 95)
            lab, st, ty = labels[keep], s[keep], types[keep]
            row = {"auroc": auroc(lab, st), "good_rej_1": float((st[lab == 0] > t1).mean()),
                   "caught_1": float((st[lab == 1] > t1).mean()), "caught_5": float((st[lab == 1] > t5).mean())}
            for d in sorted(set(ty) - {""}):
                m = (ty == d) | (lab == 0)
                row[d] = [round(auroc(lab[m], st[m]), 3), round(float((st[ty == d] > t1).mean()), 3)]
            rows["+".join(combo)] = row
            print(f"{name:10s} {'+'.join(combo):14s}",
                  json.dumps({k: (round(v, 3) if isinstance(v, float) else v) for k, v in row.items()}), flush=True)
        return rows

    result = {"val (B good, all defective)": report("val", vs, vl, vt, (vl == 1) | np.isin(np.arange(len(vl)), B))}
    nm, nj, nl, nt = run(new_val)
    result[new_val] = report("new-kinds", scores(nm, nj), nl, nt, np.ones(len(nl), bool))
    json.dump(result, open(out, "w"), indent=1)


if __name__ == "__main__":
    main()
