"""The shipped file's share of good parts rejected at its threshold through rule 60's guards, beside the same parts as
rendered. Usage: python guard.py RUNS_DIR (reads RUNS_DIR/eval-guard-*/)."""
import json
import sys
from pathlib import Path

import numpy as np

from station.eval_compare import read_scores

runs = Path(sys.argv[1])
print("| guard | set | good parts rejected | the same parts as rendered |")
print("|---|---|---|---|")
for name, changed, plain in (("panel at half its radiance", "pb-half-1154", "line-panel-heldout-1154"),
                             ("lens blur 0.7 px", "so-blurff-1157", "line-panel-heldout-1157"),
                             ("all five camera imperfections", "so-allff-1159", "line-panel-heldout-1159")):
    shares = []
    for s in (changed, plain):
        d = runs / f"eval-guard-{s}"
        th = float(json.loads((d / "eval.json").read_text())["threshold"])
        good = np.array([score for label, _, score in read_scores(d).values() if label == 0])
        shares.append(f"{100 * (good > th).mean():.1f} % ({int((good > th).sum())} of {len(good)})")
    print(f"| {name} | {changed} | {shares[0]} | {shares[1]} |")
