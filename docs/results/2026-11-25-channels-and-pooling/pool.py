"""Rule 17: pooling a part's highest windows instead of its single worst one (rule-17.md; the page
docs/results/2026-11-25-channels-and-pooling.md).

    PYTHONPATH=. OMP_NUM_THREADS=2 .venv/bin/python docs/results/2026-11-25-channels-and-pooling/pool.py \
        data/line-polar-train data/line-polar-val data/line-polar-heldout data/line-polar-heldout-212 OUT.json

The shipped statistic's per-place map, recomputed from the refitted model's signed maps as in whiten.py (same
fit, same box and calibration), pooled four ways: the maximum (shipped), the mean of the 10 or 40 highest values,
and the excess mass (the sum of map - 1 above 1, plus the maximum). Thresholds and shifts as whiten.py.
"""
from __future__ import annotations

import copy
import json
import sys

import numpy as np
import torch
from sklearn.metrics import roc_auc_score

from model.draem.checkpoint import load_checkpoint
from model.draem.shifts import SHIFTS, Channels, shift

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from whiten import PRIORS, TYPES, Statistic, bootstrap_auroc, load, rejected, report, signed_maps, windows

POOLS = ("max", "top-10 mean", "top-40 mean", "excess mass")


def pooled(st: Statistic, signed: np.ndarray, judged: np.ndarray, eroded: np.ndarray) -> dict[str, np.ndarray]:
    """Each pooling of the per-place map of ``signed`` parts."""
    m = np.maximum((windows(signed, st.white, st.name) - st.loc) / st.spread, 0.0) * (judged & eroded)
    flat = -np.sort(-m.reshape(len(m), -1), axis=1)
    return {"max": flat[:, 0], "top-10 mean": flat[:, :10].mean(1), "top-40 mean": flat[:, :40].mean(1),
            "excess mass": np.maximum(flat - 1.0, 0.0).sum(1) + flat[:, 0]}


def main() -> None:
    train_dir, val_dir, heldout_dir, heldout2_dir, out = sys.argv[1:6]
    torch.set_num_threads(2)
    xt, _, _, mt = load(train_dir, "train", good_only=True)
    model = copy.deepcopy(load_checkpoint("model/weights/default").detector.variation)
    train = np.delete(model.fit(xt, mt), model.dolp, axis=1)
    del xt
    eroded = model.scored_region()
    st = Statistic("shipped", train, np.zeros((1, 1, 3, 3), np.float32), model.region.numpy())
    del train
    xv, lv, kv, _ = load(val_dir, "val")
    sv, jv, zv = signed_maps(model, xv)
    val = pooled(st, sv, jv, eroded)
    print(f"check: max pooling vs zmaps on validation: AUROC {roc_auc_score(lv, val['max']):.4f} vs "
          f"{roc_auc_score(lv, zv):.4f}", flush=True)
    result: dict = {"val": {}, "set 212": {}, "set 202 shifts": {}}
    for n in POOLS:
        r = report(val[n], lv, val[n], lv, kv)
        r["gain"], r["gain_se"] = bootstrap_auroc(lv, val["max"], val[n])
        result["val"][n] = r
        print(f"val {n:12s} AUROC {r['auroc']:.4f} (gain {r['gain']:+.4f} se {r['gain_se']:.4f}) "
              f"1 % {r['caught0.01']:.1%} 5 % {r['caught0.05']:.1%} "
              + " ".join(f"{t[:5]} {r[t]:.3f}" for t in TYPES), flush=True)
    del sv, xv
    xh, lh, kh, _ = load(heldout2_dir, "test")
    sh, jh, _ = signed_maps(model, xh)
    held = pooled(st, sh, jh, eroded)
    for n in POOLS:
        r = report(val[n], lv, held[n], lh, kh)
        r["gain"], r["gain_se"] = bootstrap_auroc(lh, held["max"], held[n])
        result["set 212"][n] = r
        print(f"set 212 {n:12s} AUROC {r['auroc']:.4f} (gain {r['gain']:+.4f} se {r['gain_se']:.4f}) "
              f"1 % {r['caught0.01']:.1%} ({r['fr0.01']:.1%}) 5 % {r['caught0.05']:.1%} ({r['fr0.05']:.1%}) "
              + " ".join(f"{t[:5]} {r[t]:.3f}" for t in TYPES), flush=True)
    del xh, sh
    xh, lh, kh, _ = load(heldout_dir, "test")
    ch = Channels.of(PRIORS)
    for name in SHIFTS:
        sh, jh, _ = signed_maps(model, torch.from_numpy(shift(name, xh.numpy(), ch)))
        held = pooled(st, sh, jh, eroded)
        result["set 202 shifts"][name] = {}
        for n in POOLS:
            s = held[n]
            r = {"auroc": float(roc_auc_score(lh, s)), **rejected(val[n], lv, s[lh == 0])}
            if name == "none":
                r.update(report(val[n], lv, s, lh, kh))
            result["set 202 shifts"][name][n] = r
            print(f"202 {name:13s} {n:12s} AUROC {r['auroc']:.4f} good rejected at 1 % {r['fr0.01']:.1%} "
                  f"5 % {r['fr0.05']:.1%} own {r['fr_own']:.1%}", flush=True)
        with open(out, "w") as f:
            json.dump(result, f, indent=1)


if __name__ == "__main__":
    main()
