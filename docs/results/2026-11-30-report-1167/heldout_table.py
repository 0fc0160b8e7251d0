"""Held-out types per report set: each type scored by the file whose look network never saw it (heldout-1167.sh).

Usage (repository root): python docs/results/2026-11-30-report-1167/heldout_table.py
Per type and report set: its image AUROC against the set's good parts, and at the file's own 1 % threshold (set on
data/line-pv-val's good parts, held fixed) the good parts rejected and that type's parts caught; beside it the
shipped file, which saw every type.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from model.draem.metrics import auroc
from station.eval_compare import read_report, read_scores

TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")
SETS = {  # report set -> (the shipped file's report, the folder holding eval-H-<type>)
    "1165": ("model/weights/default-eval", "docs/results/2026-11-29-finish-vary/heldout"),
    "1167": ("docs/results/2026-11-30-report-1167/eval-1167", "docs/results/2026-11-30-report-1167/heldout-1167"),
}


def cells(folder: str, kind: str) -> str:
    """'AUROC (caught at 1 %; good rejected)' of one type in one report."""
    if not (Path(folder) / "scores.csv").exists():
        return "not measured | "
    thr = read_report(folder)["threshold"]
    r = read_scores(folder)
    y = np.array([v[0] for v in r.values()], bool)
    t = np.array([v[1] for v in r.values()])
    s = np.array([v[2] for v in r.values()])
    keep = ~y | (t == kind)
    return (f"{auroc(y[keep], s[keep]):.3f} | {np.mean(s[y & (t == kind)] > thr):.0%} "
            f"({np.mean(s[~y] > thr):.1%} good rejected)")


def main() -> None:
    print("| type | set | held out: image AUROC | held out: caught at 1 % | shipped file (saw it): image AUROC "
          "| shipped: caught at 1 % |")
    print("|---|---|---|---|---|---|")
    for kind in TYPES:
        for name, (shipped, held) in SETS.items():
            print(f"| {kind} | {name} | {cells(f'{held}/eval-H-{kind}', kind)} | {cells(shipped, kind)} |")


if __name__ == "__main__":
    main()
