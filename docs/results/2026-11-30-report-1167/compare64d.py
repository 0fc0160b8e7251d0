"""Check 64d (plan-64d.md): two files' `station eval` reports on the same parts, each at its own threshold.

Usage (repository root): python docs/results/2026-11-30-report-1167/compare64d.py EVAL_U EVAL_S
Prints good parts rejected and defective parts caught at each report's own threshold, per type, and the paired image
AUROC change S - U with its bootstrap SE (model.draem.metrics.paired_auroc_gains).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from model.draem.metrics import paired_auroc_gains
from station.eval_compare import read_scores


def main() -> None:
    dirs = sys.argv[1:3]
    thr = [json.loads((Path(d) / "eval.json").read_text())["threshold"] for d in dirs]
    u, s = (read_scores(d) for d in dirs)
    idx = sorted(u)
    assert sorted(s) == idx and all(u[i][:2] == s[i][:2] for i in idx), "the reports are not on the same parts"
    y = np.array([u[i][0] for i in idx], bool)
    t = np.array([u[i][1] for i in idx])
    a, b = (np.array([r[i][2] for i in idx]) for r in (u, s))
    types = sorted(set(t[y]))
    print(f"{len(idx)} parts: {int((~y).sum())} good, {int(y.sum())} defective.\n")
    print("| file | own threshold | good parts rejected | defective parts caught | " + " | ".join(types) + " |")
    print("|---|---|---|---|" + "---|" * len(types))
    for name, sc, th in (("U " + dirs[0], a, thr[0]), ("S " + dirs[1], b, thr[1])):
        per = " | ".join(f"{np.mean(sc[y & (t == k)] > th):.0%}" for k in types)
        print(f"| {name} | {th:.4f} | {int((sc[~y] > th).sum())} of {int((~y).sum())} ({np.mean(sc[~y] > th):.1%}) | "
              f"{int((sc[y] > th).sum())} of {int(y.sum())} ({np.mean(sc[y] > th):.1%}) | {per} |")
    print("\n| type | defective | image AUROC, U | S | S - U (paired SE) |\n|---|---|---|---|---|")
    for r in paired_auroc_gains(y, np.where(y, t, ""), a, b):
        print(f"| {r['type']} | {r['defective']} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} "
              f"({r['se']:.3f}) |")


if __name__ == "__main__":
    main()
