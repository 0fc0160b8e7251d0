"""Stop 60's window screens, shared part: each statistic is a map per part computed from the signed z of the shipped
file's variation model (as ``zmaps`` computes z: clusters, noise level; no second look, no networks), calibrated as
log_screen.py of 2026-11-29-curvature: per-pixel median / 95th percentile (blurred) from the even good parts of the val
split (A); each statistic's scores divided by its A 99th percentile (so a max of several is fair); thresholds at 1 %
and 5 % from the odd good parts (B). Selection on the val split only; used held-out sets are printed beside it.
``screen(stats, combos)`` reads MODEL VAL OUT.json [HELDOUT...] from the command line (a HELDOUT given as DATA:val is
scored on its val split, e.g. a validation set of other kinds: stop 76); ``stats(z, judged)`` maps
(C, H, W) z (zero outside judged) to {name: (H, W) map}; ``combos`` lists tuples of names, each scored as the
larger of its statistics."""
import json
import sys
from collections.abc import Callable

import cv2
import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import auroc
from model.draem.variation import NOISE_CAP, WINDOW_BLUR_PX, WINDOW_QUANTILE
from station.evaluation import model_split


def screen(stats: Callable[[np.ndarray, np.ndarray], dict[str, np.ndarray]],
           combos: Callable[[list[str]], list[tuple[str, ...]]]) -> None:
    model, val, out, *tests = sys.argv[1:]
    ck = load_checkpoint(model)
    vm = ck.detector.variation

    def z_of(x):
        r, coef, judged, _ = vm._judged_residual(x)
        z = vm.used(vm.clustered(r, coef))
        level = vm.noise_level(np.abs(z), judged)
        return (np.nan_to_num(z / (level if 1.0 < level <= NOISE_CAP else 1.0)) * judged).astype(np.float32), judged

    def run(data, split):
        s = model_split(ck, model, data, split)
        maps, judged = {}, []
        for i, x in enumerate(s.priors.numpy()):
            z, j = z_of(x)
            judged.append(j)
            for k, v in stats(z, j).items():
                maps.setdefault(k, []).append(v.astype(np.float32))
            if i % 100 == 0:
                print(f"{data} {i}/{len(s.priors)}", flush=True)
        return ({k: np.stack(v) for k, v in maps.items()}, np.stack(judged), np.asarray(s.label),
                np.array(s.defect_type))

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
    rows_of = combos(list(vs))

    def combined(sc, combo):
        return np.max([sc[k] / norm[k] for k in combo], 0)

    def report(name, sc, labels, types, keep):
        rows = {}
        for combo in rows_of:
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
        data, _, split = t.partition(":")
        tm, tj, tl, tt = run(data, split or "test")
        result[t] = report(t.split("/")[-1], scores(tm, tj), tl, tt, np.ones(len(tl), bool))
    json.dump(result, open(out, "w"), indent=1)
