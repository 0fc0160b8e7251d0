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


def main() -> None:
    args = sys.argv[1:]
    print("| eval | type | face | n | image AUROC |")
    print("|---|---|---|---|---|")
    for eval_dir, data in zip(args[::2], args[1::2], strict=True):
        rows = list(csv.DictReader(open(Path(eval_dir) / "scores.csv")))
        good = np.array([float(r["score"]) for r in rows if r["label"] == "0"])
        groups: dict[tuple[str, str], list[float]] = {}
        for r in rows:
            if r["label"] != "1":
                continue
            g = np.load(Path(data) / "samples" / f"{int(r['index']):06d}" / "gt.npz")
            m = g["defect_mask"] > 0
            face = "top" if m.any() and np.median(g["normal"][m][:, 2]) < 0.7 else "front"
            groups.setdefault((r["defect_type"], face), []).append(float(r["score"]))
        for (t, face), s in sorted(groups.items()):
            print(f"| {Path(eval_dir).name} | {t} | {face} | {len(s)} | {auroc(np.array(s), good):.3f} |")


if __name__ == "__main__":
    main()
