"""Told where, by face: per defect type and face (the bright-field study's `faces.py`: the defect's true normal),
the share the localised oracle separates at 1 % (`scores.csv`'s `separable`) and the share the model caught at the
validation 1 % threshold. Usage: python faces_told.py EVAL_DIR DATA_DIR THRESHOLD"""

from __future__ import annotations

import csv
import importlib.util
import sys
from pathlib import Path

import numpy as np

spec = importlib.util.spec_from_file_location("faces", Path(__file__).parents[1] / "2026-11-27-bright-field/faces.py")
faces = importlib.util.module_from_spec(spec)
spec.loader.exec_module(faces)

eval_dir, data, threshold = sys.argv[1], sys.argv[2], float(sys.argv[3])
rows: dict[tuple[str, str], list[tuple[int, bool]]] = {}
for r in csv.DictReader(open(Path(eval_dir) / "scores.csv")):
    if r["label"] == "1" and r["separable"] != "":
        g = np.load(Path(data) / "samples" / f"{int(r['index']):06d}" / "gt.npz")
        key = (r["defect_type"], faces.face(g["normal"], g["defect_mask"] > 0))
        rows.setdefault(key, []).append((int(r["separable"]), float(r["score"]) > threshold))
print("| type | face | defects | separable at 1 % | caught at 1 % |")
print("|---|---|---|---|---|")
for key in sorted(rows):
    v = np.array(rows[key])
    print(f"| {key[0]} | {key[1]} | {len(v)} | {v[:, 0].mean():.0%} | {v[:, 1].mean():.0%} |")
