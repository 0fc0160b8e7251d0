"""plan.md, development reading through the implementation (seed 1201 and validation sets only): the shipped file
and C (the shipped file plus `station shape`'s outline check) on flash-dev-1201 by edge and face from `station eval`'s
reports, and the good parts of the validation sets above each file's threshold. Run from the repository's root after
both reports exist (runs/outline/eval-dev, runs/outline/evalC-dev)."""

import csv
import json
import sys
from collections import defaultdict

import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.detector import Detector
from sim.dataset import sample_dir
from station.evaluation import model_split

SETS = {"shipped": "runs/outline/eval-dev", "C": "runs/outline/evalC-dev"}
for name, folder in SETS.items():
    thr = json.load(open(f"{folder}/eval.json"))["threshold"]
    groups: dict[str, list[int]] = defaultdict(lambda: [0, 0])
    with open(f"{folder}/scores.csv") as f:
        for row in csv.DictReader(f):
            caught = float(row["score"]) > thr
            if row["label"] == "0":
                groups["good rejected"][0] += caught
                groups["good rejected"][1] += 1
                continue
            d = json.loads((sample_dir("data/flash-dev-1201", int(row["index"])) / "params.json").read_text())
            d = d["defect"]
            for key in ("flash, all", f"{row['face']} {d['edge']}"):
                groups[key][0] += caught
                groups[key][1] += 1
    print(f"{name}: threshold {thr:.4f}")
    for key in sorted(groups):
        c, n = groups[key]
        print(f"    {key:18s} {c:4d} of {n:4d}  {100 * c / n:5.1f} %")


def scores(det: Detector, x) -> np.ndarray:
    return np.concatenate([det.predict(x[i:i + 16]).score.float().numpy() for i in range(0, len(x), 16)])


for data in ("data/warp-val-1199", "data/line-pv-val"):
    line = [data]
    for name, path in (("shipped", "model/weights/default"), ("C", "runs/outline/C")):
        ck = load_checkpoint(path)
        sp = model_split(ck, path, data, "val", good_only=True)
        s = scores(ck.detector.eval(), sp.priors)
        line.append(f"{name} {int((s > ck.threshold).sum())} of {len(s)} good rejected")
    print("; ".join(line), flush=True)
sys.exit(0)
