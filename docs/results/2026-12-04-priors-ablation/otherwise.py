"""The addendum's table (plan.md): R, RAD and the shipped file E63 on seed 1191 as built and rendered otherwise.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-04-priors-ablation/otherwise.py > .../otherwise.txt

Each file at its stored threshold (a part is rejected when its score is above it): good parts rejected, defective
parts caught, image AUROC; and caught at 2 good parts rejected (matched.py's measure).
"""
import csv
import json
from pathlib import Path

import numpy as np

from model.draem.metrics import auroc

HERE = Path(__file__).parent
REPORTS = {"as built": {"R": "eval-R-1191", "RAD": "eval-RAD-1191", "E63": "shipped/eval-E63-1191"},
           **{name: {m: f"otherwise/eval-{m}-{key}" for m in ("R", "RAD", "E63")}
              for name, key in (("GGX lobe", "ggx"), ("duller plastic", "rough"))}}


def row(folder: str) -> str:
    rows = sorted(csv.DictReader(open(HERE / folder / "scores.csv")), key=lambda r: int(r["index"]))
    y = np.array([int(r["label"]) for r in rows])
    s = np.array([float(r["score"]) for r in rows])
    t = json.load(open(HERE / folder / "eval.json"))["threshold"]
    good = np.sort(s[y == 0])[::-1]
    return (f"{int((s[y == 0] > t).sum())} of {int((y == 0).sum())} good rejected, "
            f"{100 * (s[y == 1] > t).mean():.1f} % caught; AUROC {auroc(y, s):.3f}; "
            f"at 2 good rejected {100 * (s[y == 1] > good[2]).mean():.1f} %")


def main() -> None:
    for rendering, models in REPORTS.items():
        for model, folder in models.items():
            print(f"{rendering:15s} {model:4s} {row(folder)}")


if __name__ == "__main__":
    main()
