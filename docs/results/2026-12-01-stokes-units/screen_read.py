"""Two models' ``station eval`` scores on the two validation sets (seeds 303 and 1176): image AUROC and the share
caught at 1 % / 5 %, each threshold from the other set's good parts, per type and face (top: the horizontal top
face, which mirrors the panel).

    python screen_read.py DIR Fv Pv    # DIR/eval-<model>-<set>/scores.csv
"""
import csv
import os
import sys

import numpy as np
from sklearn.metrics import roc_auc_score

from model.draem.metrics import false_reject_threshold

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "2026-12-01-aolp-top-face"))
from aolp_screen import sample_meta

SETS = ["line-pv-val", "line-pv-val-1176"]
GROUPS = ["all", "dent", "dent-top", "scratch", "scratch-top", "stain", "chip", "missing_stud"]


def meta(s: str) -> dict[int, tuple[int, str, str]]:
    """index -> (label, type, face) of the val split (``aolp_screen.sample_meta``'s face)."""
    out = {}
    for n in sorted(os.listdir(f"data/{s}/samples")):
        m = sample_meta(f"data/{s}", n)
        if m["split"] == "val":
            out[int(n)] = (m["label"], m["type"] if m["label"] else "good", m["face"])
    return out


def main(root: str, models: list[str]) -> None:
    info = {s: meta(s) for s in SETS}
    scores = {(m, s): {int(r["index"]): float(r["score"]) for r in csv.DictReader(
        open(f"{root}/eval-{m}-{s}/scores.csv"))} for m in models for s in SETS}

    def point(m: str, s: str, rate: float) -> float:
        return false_reject_threshold([v for i, v in scores[(m, s)].items() if info[s][i][0] == 0], rate)

    for m in models:
        print(f"== {m}")
        for k, s in enumerate(SETS):
            other, sc = SETS[1 - k], scores[(m, s)]
            good = [v for i, v in sc.items() if info[s][i][0] == 0]
            cells = []
            for g in GROUPS:
                d = np.array([v for i, v in sc.items()
                              if info[s][i][0] and g in ("all", info[s][i][1], f"{info[s][i][1]}-{info[s][i][2]}")])
                auc = roc_auc_score([0] * len(good) + [1] * len(d), good + list(d))
                cells.append(f"{g} ({len(d)}) {auc:.3f} {np.mean(d > point(m, other, 0.01)):.0%}/"
                             f"{np.mean(d > point(m, other, 0.05)):.0%}")
            rejected = np.mean(np.array(good) > point(m, other, 0.01))
            print(f"  {s} (good {len(good)}, rejected at the other's 1 %: {rejected:.1%}): " + ", ".join(cells))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
