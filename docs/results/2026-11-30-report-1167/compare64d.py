"""Check 64d (plan-64d.md): two files' `station eval` reports on the same parts, each at its own threshold.

Usage (repository root): python docs/results/2026-11-30-report-1167/compare64d.py EVAL_U EVAL_S [NAME_U NAME_S]
Prints good parts rejected and defective parts caught at each report's own threshold, per type, and the paired image
AUROC change S - U with its bootstrap SE (score64c's tables). Check 65 names its files (default U and S).
"""

from __future__ import annotations

import sys

import numpy as np
from score64c import paired_table, row

from station.eval_compare import read_report, read_scores


def main() -> None:
    dirs = sys.argv[1:3]
    nu, ns = sys.argv[3:5] or ("U", "S")
    thr = [read_report(d)["threshold"] for d in dirs]
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
    print(row(f"{nu} {dirs[0]}", y, t, a, thr[0]))
    print(row(f"{ns} {dirs[1]}", y, t, b, thr[1]))
    paired_table(y, t, a, b, nu, ns, f"{ns} - {nu}")

if __name__ == "__main__":
    main()
