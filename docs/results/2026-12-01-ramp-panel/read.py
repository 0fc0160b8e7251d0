"""The ramp screen's reading (plan.md, plan-2.md): two models' ``station eval`` scores on twin validation sets (the
same parts under two panels): image AUROC per group with the paired bootstrap SE of the difference
(``model.draem.metrics.paired_auroc_gains``), caught at 1 % and 5 % of each set's own good parts
(``false_reject_threshold``). Several pairs of sets (each four arguments) are pooled: their parts keyed by the pair,
each set's own good parts setting its caught-at thresholds.

    python read.py data/line-pv-val F/scores.csv data/ramp-pv-val R/scores.csv > read.md
    python read.py A1 FA1 B1 RB1 A2 FA2 B2 RB2 > pooled.md
"""
import csv
import os
import sys

import numpy as np

from model.draem.metrics import false_reject_threshold, paired_auroc_gains

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "2026-12-01-aolp-top-face"))
from aolp_screen import sample_meta

GROUPS = ["all", "dent", "dent-top", "dent-other", "scratch", "scratch-top", "scratch-other", "stain", "chip",
          "missing_stud"]
RESAMPLES = 2000


def meta(root: str) -> dict[int, tuple[int, str]]:
    """index -> (label, group key type-face) of the val split (``aolp_screen.sample_meta``'s face)."""
    out = {}
    for n in sorted(os.listdir(f"{root}/samples")):
        m = sample_meta(root, n)
        if m["split"] == "val":
            out[int(n)] = (m["label"], f'{m["type"]}-{m["face"]}' if m["label"] else "good")
    return out


def scores(path: str) -> dict[int, float]:
    return {int(r["index"]): float(r["score"]) for r in csv.DictReader(open(path))}


def in_group(key: str, group: str) -> bool:
    return group == "all" or key == group or key.rsplit("-", 1)[0] == group


def caught(s: dict, info: dict, idx: list, rate: float) -> float:
    """The share of ``idx`` above each pair's own ``rate`` point on its good parts (keys (pair, index))."""
    points = {k: false_reject_threshold([s[i] for i in info if i[0] == k and info[i][0] == 0], rate)
              for k in {key[0] for key in info}}
    return float(np.mean([s[i] > points[i[0]] for i in idx]))


def load(quads: list[str]) -> tuple[dict, dict, dict]:
    """(meta, scores A, scores B) keyed by (pair, index) over every pair of twin sets."""
    info, sa, sb = {}, {}, {}
    for k in range(0, len(quads), 4):
        set_a, scores_a, set_b, scores_b = quads[k:k + 4]
        ia = meta(set_a)
        assert ia == meta(set_b), "the two sets must be twins: the same parts, labels and defects"
        a, b = scores(scores_a), scores(scores_b)
        for i, m in ia.items():
            info[(k, i)], sa[(k, i)], sb[(k, i)] = m, a[i], b[i]
    return info, sa, sb


def main(quads: list[str]) -> None:
    info, sa, sb = load(quads)
    keys = list(info)
    labels = np.array([info[i][0] for i in keys])
    a, b = np.array([sa[i] for i in keys]), np.array([sb[i] for i in keys])
    by_face = [info[i][1] if info[i][0] else "" for i in keys]
    rows = {r["type"]: r for types in ([t.rsplit("-", 1)[0] if t else "" for t in by_face], by_face)
            for r in paired_auroc_gains(labels, types, a, b, resamples=RESAMPLES, seed=0)}
    good = int((labels == 0).sum())
    print(f"{good} good parts, {len(keys) - good} defective; A = {quads[1::4]}, B = {quads[3::4]}\n")
    print("| group | n | image AUROC A | B | B - A (paired SE) | SEs | caught at 1 % A / B | at 5 % A / B |")
    print("|---|---|---|---|---|---|---|---|")
    for g in GROUPS:
        d = [i for i in keys if info[i][0] and in_group(info[i][1], g)]
        if not d:
            continue
        r = rows[g]
        print(f"| {g} | {len(d)} | {r['base']:.3f} | {r['other']:.3f} | {r['gain']:+.3f} ({r['se']:.3f}) | "
              f"{r['gain'] / max(r['se'], 1e-9):+.1f} | {caught(sa, info, d, 0.01):.0%} / "
              f"{caught(sb, info, d, 0.01):.0%} | {caught(sa, info, d, 0.05):.0%} / {caught(sb, info, d, 0.05):.0%} |")


if __name__ == "__main__":
    main(sys.argv[1:])
