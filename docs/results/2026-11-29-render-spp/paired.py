"""Check 62 (plan.md): the shipped file on the same parts of seed 1166 at 16 spp and at another spp, paired by index.

Usage (from the repository root): python docs/results/2026-11-29-render-spp/paired.py EVAL_16 EVAL_OTHER LABEL
Prints, on the parts both reports scored: good parts rejected and defective parts caught at the file's own
threshold, image AUROC, and the paired AUROC change with its bootstrap SE (model.draem.metrics.paired_auroc_gains).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from model.draem.metrics import paired_auroc_gains
from station.eval_compare import read_scores


def main() -> None:
    base_dir, other_dir, label = sys.argv[1:4]
    thr = json.loads((Path(base_dir) / "eval.json").read_text())["threshold"]
    base, other = read_scores(base_dir), read_scores(other_dir)
    common = sorted(set(base) & set(other))
    assert all(base[i][:2] == other[i][:2] for i in common), "the two reports disagree on a part's label or type"
    y = np.array([base[i][0] for i in common], bool)
    t = np.array([base[i][1] for i in common])
    a = np.array([base[i][2] for i in common])
    b = np.array([other[i][2] for i in common])
    print(f"{len(common)} parts (indices {common[0]}-{common[-1]}): {int((~y).sum())} good, {int(y.sum())} defective; "
          f"threshold {thr:.4g}\n")
    print("| set | good parts rejected | defective parts caught |\n|---|---|---|")
    for name, s in (("16 spp", a), (label, b)):
        print(f"| {name} | {int((s[~y] > thr).sum())} of {int((~y).sum())} ({np.mean(s[~y] > thr):.1%}) | "
              f"{int((s[y] > thr).sum())} of {int(y.sum())} ({np.mean(s[y] > thr):.1%}) |")
    print(f"\n| type | defective | image AUROC, 16 spp | {label} | change (paired SE) |\n|---|---|---|---|---|")
    for r in paired_auroc_gains(y, np.where(y, t, ""), a, b):
        print(f"| {r['type']} | {r['defective']} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} "
              f"({r['se']:.3f}) |")


if __name__ == "__main__":
    main()
