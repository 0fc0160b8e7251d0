"""Check 74's reading (check-74-plan.md): two files' ``station eval`` on twin held-out sets (the same parts under
two panels), each file at its own fixed threshold (its eval.json's, set on its own validation set). Per group: parts
caught by each and the paired difference with its SE (per defective part, caught B minus caught A); image AUROC and
its paired bootstrap SE (``model.draem.metrics.paired_auroc_gains``); good parts rejected by each. Labels and types
are eval's (scores.csv); the face is ``aolp_screen.sample_meta``'s.

    python read_check.py SET_A EVAL_A SET_B EVAL_B > check-74.md
"""
import csv
import json
import os
import sys

import numpy as np

from model.draem.metrics import paired_auroc_gains

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "2026-12-01-aolp-top-face"))
from aolp_screen import sample_meta

GROUPS = ["all", "dent", "dent-top", "dent-other", "scratch", "scratch-top", "scratch-other", "stain", "chip",
          "missing_stud"]


def rows(root: str, run: str) -> tuple[dict[int, tuple[int, str]], dict[int, float], float]:
    """index -> (label, type-face) and index -> score of one eval, and its file's threshold."""
    info, s = {}, {}
    for r in csv.DictReader(open(f"{run}/scores.csv")):
        i, label = int(r["index"]), int(r["label"])
        face = sample_meta(root, f"{i:06d}" if os.path.isdir(f"{root}/samples/{i:06d}") else str(i))["face"]
        info[i] = (label, f'{r["defect_type"]}-{face}' if label else "good")
        s[i] = float(r["score"])
    return info, s, float(json.load(open(f"{run}/eval.json"))["threshold"])


def in_group(key: str, group: str) -> bool:
    return group == "all" or key == group or key.rsplit("-", 1)[0] == group


def main(set_a: str, run_a: str, set_b: str, run_b: str) -> None:
    info, sa, ta = rows(set_a, run_a)
    info_b, sb, tb = rows(set_b, run_b)
    assert info == info_b, "the two sets must be twins: the same parts, labels and defects"
    keys = sorted(info)
    y = np.array([info[i][0] for i in keys])
    a, b = np.array([sa[i] for i in keys]), np.array([sb[i] for i in keys])
    ca, cb = a > ta, b > tb
    by_face = [info[i][1] if info[i][0] else "" for i in keys]
    auc = {r["type"]: r for types in ([t.rsplit("-", 1)[0] if t else "" for t in by_face], by_face)
           for r in paired_auroc_gains(y, types, a, b, resamples=2000, seed=0)}
    good = y == 0
    print(f"{int(good.sum())} good parts, {int(y.sum())} defective; A = {run_a} (threshold {ta:.4f}), "
          f"B = {run_b} (threshold {tb:.4f})\n")
    print(f"Good parts rejected: A {int(ca[good].sum())} ({ca[good].mean():.1%}), "
          f"B {int(cb[good].sum())} ({cb[good].mean():.1%}).\n")
    print("| group | n | caught A | caught B | B - A (paired SE) | SEs | image AUROC A | B | B - A (paired SE) | SEs |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for g in GROUPS:
        sel = np.array([bool(info[i][0]) and in_group(info[i][1], g) for i in keys])
        if not sel.any():
            continue
        d = cb[sel].astype(float) - ca[sel].astype(float)
        se = d.std(ddof=1) / np.sqrt(d.size) if d.size > 1 else float("nan")
        r = auc[g]
        print(f"| {g} | {int(sel.sum())} | {int(ca[sel].sum())} | {int(cb[sel].sum())} | {d.mean():+.3f} ({se:.3f}) "
              f"| {d.mean() / max(se, 1e-9):+.1f} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} "
              f"({r['se']:.3f}) | {r['gain'] / max(r['se'], 1e-9):+.1f} |")


if __name__ == "__main__":
    main(*sys.argv[1:])
