"""Rule 3 (rule.md): the residual-network candidates against the shipped statistic on validation; the same scores on
held-out set 202 and (with --held212) 212, validation thresholds held fixed.

Usage: evaluate.py OUT.json TAG... [--held212] (TAG: runs/s33/net-TAG.json; several tags are averaged as an
ensemble, each member calibrated on the good validation parts as model.draem.residual does)."""

from __future__ import annotations

import json
import sys

import numpy as np
from bootstrap import compare, held_out

args = [a for a in sys.argv[1:] if not a.startswith("--")]
out_path, tags = args[0], args[1:]
c = np.load("runs/s33/zcache.npz")
lv = c["val_label"]
nets = [json.load(open(f"runs/s33/net-{t}.json")) for t in tags]


def robust_z(good: np.ndarray, s: np.ndarray) -> np.ndarray:
    med = np.median(good)
    return (s - med) / (1.4826 * np.median(np.abs(good - med)) + 1e-9)


def candidates(split: str, statistic: np.ndarray) -> dict[str, np.ndarray]:
    nv = np.mean([robust_z(np.array(n["val"])[lv == 0], np.array(n[split])) for n in nets], 0)
    sv = robust_z(c["val_score"][lv == 0], statistic)
    return {"shipped": sv, "ensemble": nv, "max": np.maximum(sv, nv), "sum": sv + nv}


val = candidates("val", c["val_score"])
result = {"tags": tags, "validation": compare(lv, c["val_type"], val)}
sets = [("held", c)] + ([("held212", np.load("runs/s33/zcache212.npz"))] if "--held212" in sys.argv else [])
for name, cc in sets:
    result[name] = held_out(cc["held_label"], cc["held_type"], candidates(name, cc["held_score"]), lv, val, name)
json.dump(result, open(out_path, "w"), indent=1)
