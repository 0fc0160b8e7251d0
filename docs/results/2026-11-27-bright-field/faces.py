"""Rule 25, after step 2: image AUROC per defect type and face, from each line's `station eval` scores.

A defect's face is read from its ground-truth normal (camera frame, median over the defect's pixels): z < 0.7 is
the top face (z ~ 0.56 at this camera), else a front face (~ 0.83). Each group's defective parts against all good
parts of the same set. Usage: python faces.py EVAL_DIR DATA_DIR [EVAL_DIR DATA_DIR ...]
"""

from __future__ import annotations

import csv
import sys
from pathlib import Path

import numpy as np


def auroc(pos: np.ndarray, neg: np.ndarray) -> float:
    """P(a defective part scores above a good one), ties half."""
    return float(((pos[:, None] > neg[None, :]) + 0.5 * (pos[:, None] == neg[None, :])).mean())


TOP_FACE_Z = 0.7
"""A defect whose ground-truth normal (camera frame, median over its pixels) has z below this lies on the top face
(z ~ 0.56 at this camera), else on a front face (~ 0.83)."""


def face(normal: np.ndarray, mask: np.ndarray) -> str:
    """"top" or "front" for the defect ``mask`` (H, W bool) on ``normal`` (H, W, 3, camera frame)."""
    return "top" if mask.any() and np.median(normal[mask][:, 2]) < TOP_FACE_Z else "front"


def faces_of(eval_dir: str, data: str) -> tuple[dict[int, float], dict[int, tuple[str, str]]]:
    """Each part's score in a `station eval` report, and each defective part's (defect type, face)."""
    scores, groups = {}, {}
    for r in csv.DictReader(open(Path(eval_dir) / "scores.csv")):
        i = int(r["index"])
        scores[i] = float(r["score"])
        if r["label"] == "1":
            g = np.load(Path(data) / "samples" / f"{i:06d}" / "gt.npz")
            groups[i] = (r["defect_type"], face(g["normal"], g["defect_mask"] > 0))
    return scores, groups


def main() -> None:
    args = sys.argv[1:]
    print("| eval | type | face | n | image AUROC |")
    print("|---|---|---|---|---|")
    for eval_dir, data in zip(args[::2], args[1::2], strict=True):
        scores, groups = faces_of(eval_dir, data)
        good = np.array([s for i, s in scores.items() if i not in groups])
        for key in sorted(set(groups.values())):
            s = np.array([scores[i] for i, k in groups.items() if k == key])
            print(f"| {Path(eval_dir).name} | {key[0]} | {key[1]} | {len(s)} | {auroc(s, good):.3f} |")


if __name__ == "__main__":
    main()
