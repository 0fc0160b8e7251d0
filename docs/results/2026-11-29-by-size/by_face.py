"""Which defects of seed 1165 the shipped file catches, by face and by the defect's pixels in the frame.

A defect's face is rule 25's (`../2026-11-27-bright-field/faces.py`: its ground-truth normal, camera frame, median
over its pixels; the top face mirrors the bright-field panel, the front faces mirror the belt). Caught: score above
the file's own threshold, the station's rule. Usage (from the repository root):
    python docs/results/2026-11-29-by-size/by_face.py EVAL_DIR DATA_DIR
"""

from __future__ import annotations

import csv
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "2026-11-27-bright-field"))
from faces import auroc, faces_of

SMALL_PX = 400
"""A defect with fewer pixels than this in the 640 x 480 frame is 'small': under 64 px at the model's 96 x 192."""


def main() -> None:
    eval_dir, data = sys.argv[1:3]
    thr = json.loads((Path(eval_dir) / "eval.json").read_text())["threshold"]
    scores, groups = faces_of(eval_dir, data)
    visible = {}
    for r in csv.DictReader(open(Path(eval_dir) / "scores.csv")):
        if r["label"] == "1":
            params = json.loads((Path(data) / "samples" / f"{int(r['index']):06d}" / "params.json").read_text())
            visible[int(r["index"])] = params["defect"]["visible_px"]
    good = np.array([s for i, s in scores.items() if i not in groups])
    print(f"| type | face | defects | image AUROC | caught | small (< {SMALL_PX} px): defects, caught "
          f"| larger: defects, caught |\n|---|---|---|---|---|---|---|")
    for key in sorted(set(groups.values())):
        idx = [i for i, k in groups.items() if k == key]
        s = np.array([scores[i] for i in idx])
        small = [i for i in idx if visible[i] < SMALL_PX]
        large = [i for i in idx if visible[i] >= SMALL_PX]

        def caught(part: list[int]) -> str:
            return f"{len(part)}, {np.mean([scores[i] > thr for i in part]):.0%}" if part else "0, -"

        print(f"| {key[0]} | {key[1]} | {len(idx)} | {auroc(s, good):.3f} | {np.mean(s > thr):.0%} | "
              f"{caught(small)} | {caught(large)} |")
    well = [i for i, k in groups.items() if k[1] == "top" and visible[i] >= SMALL_PX]
    parts = {"shown well (top face, >= 400 px)": well,
             "shown well, without missing studs": [i for i in well if groups[i][0] != "missing_stud"],
             "the rest": [i for i in groups if i not in well]}
    print()
    for name, part in parts.items():
        n = sum(scores[i] > thr for i in part)
        print(f"{name}: {n} of {len(part)} caught ({n / len(part):.1%})" if part else f"{name}: none")


if __name__ == "__main__":
    main()
