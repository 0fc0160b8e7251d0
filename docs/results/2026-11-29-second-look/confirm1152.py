"""Seed 1152, the shipped file against the file before (`station eval` of each: their scores.csv), thresholds from
the validation set (each file's 1 % and 5 % thresholds as its eval.json's note prints them, 4 digits; the point
figures are checked against the report's own), paired bootstrap SEs of the difference over the set's parts (1000
resamples). Usage: python confirm1152.py X_EVAL_DIR C_EVAL_DIR"""

from __future__ import annotations

import csv
import json
import sys

import numpy as np

from model.draem.metrics import auroc


def read(d: str) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict[str, float]]:
    with open(f"{d}/scores.csv") as f:
        rows = list(csv.DictReader(f))
    note = json.load(open(f"{d}/eval.json"))["industrial_note"]  # "1 % -> 0.9757, ... 5 % -> 0.5276, ..."
    thr = {fr: float(note.split(f"{fr} % -> ")[1].split(",")[0]) for fr in ("1", "5")}
    return (np.array([int(r["label"]) for r in rows]), np.array([r["defect_type"] for r in rows]),
            np.array([float(r["score"]) for r in rows]), thr)


yx, tx, sx, thx = read(sys.argv[1])
yc, tc, sc, thc = read(sys.argv[2])
assert (yx == yc).all() and (tx == tc).all()


def figs(idx: np.ndarray) -> dict[str, float]:
    y, out = yx[idx], {}
    for k, s, th in (("X", sx, thx), ("C", sc, thc)):
        out[f"{k} auroc"] = auroc(y, s[idx])
        for fr, t in th.items():
            out[f"{k} caught {fr}"] = float(np.mean(s[idx][y == 1] > t))
    return out


idx = np.arange(len(yx))
p = figs(idx)
rng = np.random.default_rng(1152)
boot = [figs(rng.choice(idx, len(idx))) for _ in range(1000)]
for k, d in (("X", sys.argv[1]), ("C", sys.argv[2])):
    row = json.load(open(f"{d}/eval.json"))["industrial"][0]
    assert abs(row["caught_at_1%_false_rejects"] - p[f"{k} caught 1"]) < 1e-9, (k, row, p)
    assert abs(row["caught_at_5%_false_rejects"] - p[f"{k} caught 5"]) < 1e-9, (k, row, p)
print(f"seed 1152: {int((yx == 0).sum())} good, {int(yx.sum())} defective; thresholds X {thx}, C {thc}")
for key in ["auroc", *(f"caught {fr}" for fr in thx)]:
    d = np.std([b[f"X {key}"] - b[f"C {key}"] for b in boot])
    x, c = p[f"X {key}"], p[f"C {key}"]
    print(f"{key}: X {x:.4f}, C {c:.4f}, X - C {x - c:+.4f} (SE {d:.4f})")
