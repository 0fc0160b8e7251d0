"""plan.md's held-out reading, from run.sh's `station eval` reports: B (the shipped file before) and S (with the
outline check) at each file's threshold, on seed 1202 (flash) by edge, face and width, and on seed 1197 (the five
kinds) by type; good parts rejected on both. Run from this folder (run.sh does)."""

import csv
import json
from collections import defaultdict
from pathlib import Path

from sim.dataset import sample_dir

ROOT = Path("../../..")


def read(tag: str, data: str) -> tuple[float, dict[str, list[int]]]:
    thr = json.loads(Path(f"eval/{tag}/eval.json").read_text())["threshold"]
    groups: dict[str, list[int]] = defaultdict(lambda: [0, 0])
    with open(f"eval/{tag}/scores.csv") as f:
        for row in csv.DictReader(f):
            caught = float(row["score"]) > thr
            keys = ["good parts rejected"] if row["label"] == "0" else ["defective, all"]
            if row["label"] == "1":
                d = json.loads((sample_dir(ROOT / data, int(row["index"])) / "params.json").read_text())["defect"]
                if d["type"] == "flash":
                    w = "0.2-0.4" if d["width_mm"] < 0.4 else "0.4-0.7" if d["width_mm"] < 0.7 else "0.7-1.0"
                    keys += [f"{row['face']} face, {d['edge']} edge", f"width {w} mm"]
                else:
                    keys.append(d["type"])
            for k in keys:
                groups[k][0] += caught
                groups[k][1] += 1
    return thr, groups


for seed, data in (("1202", "data/flash-1202"), ("1197", "data/line-heldout-1197")):
    (tb, b), (ts, s) = read(f"B-{seed}", data), read(f"S-{seed}", data)
    print(f"seed {seed} ({data}); thresholds: B {tb:.4f}, S {ts:.4f}")
    print(f"    {'':28s} {'B (before)':>16s} {'S (outline check)':>18s}")
    for k in sorted(b, key=lambda k: (k != "defective, all", k == "good parts rejected", k)):
        print(f"    {k:28s} {b[k][0]:4d} of {b[k][1]:4d} {100 * b[k][0] / b[k][1]:5.1f} %"
              f"   {s[k][0]:4d} of {s[k][1]:4d} {100 * s[k][0] / s[k][1]:5.1f} %")
