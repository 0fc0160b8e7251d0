"""plan.md, reading 1: the shipped file's flash caught at its threshold by the fin's edge (top or bottom), face and
width, from `station eval`'s scores.csv and each part's params.json. Run from the repository's root."""

import csv
import json
import sys
from collections import defaultdict
from pathlib import Path

from sim.dataset import sample_dir

HERE = Path(__file__).parent
ev = json.loads((HERE / "eval/line/eval.json").read_text())
threshold = ev["threshold"]
groups: dict[str, list[int]] = defaultdict(lambda: [0, 0])
with open(HERE / "eval/line/scores.csv") as f:
    for row in csv.DictReader(f):
        if row["label"] != "1":
            continue
        d = json.loads((sample_dir("data/flash-1200", int(row["index"])) / "params.json").read_text())["defect"]
        caught = float(row["score"]) > threshold
        width = "0.2-0.4" if d["width_mm"] < 0.4 else "0.4-0.7" if d["width_mm"] < 0.7 else "0.7-1.0"
        for key in ("all", f"edge {d['edge']}", f"face {row['face']}", f"{row['face']} {d['edge']}",
                    f"width {width} mm", f"{d['edge']}, width {width} mm"):
            groups[key][0] += caught
            groups[key][1] += 1
print(f"threshold {threshold:.4f} (the file's)")
for key in sorted(groups):
    c, n = groups[key]
    print(f"{key:28s} {c:4d} of {n:4d}  {100 * c / n:5.1f} %")
sys.exit(0)
