"""plan-2.md's figure: defective parts caught against good parts rejected on H (seed 1216), the shipped file and the
file made on 1,800 training parts, each file's own 1 % threshold marked. Usage: python plan-2-plot.py (from the
repository's root; reads eval-2/*/scores.csv and the threshold in eval.json, writes plan-2.png)."""

import csv
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

HERE = Path(__file__).parent
ARMS = (("shipped", "shipped (fit on 375 good parts)"), ("new", "1,800 training parts (fit on 751)"))


def main() -> None:
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for name, label in ARMS:
        rows = list(csv.DictReader(open(HERE / "eval-2" / name / "scores.csv")))
        thr = json.loads((HERE / "eval-2" / name / "eval.json").read_text())["threshold"]
        s = np.array([float(r["score"]) for r in rows])
        y = np.array([r["label"] == "1" for r in rows])
        ts = np.sort(np.unique(s))[::-1]
        fpr = [(s[~y] > t).mean() for t in ts]
        tpr = [(s[y] > t).mean() for t in ts]
        (line,) = ax.plot(100 * np.array(fpr), 100 * np.array(tpr), label=label)
        ax.plot(100 * (s[~y] > thr).mean(), 100 * (s[y] > thr).mean(), "o", color=line.get_color())
    ax.set_xlim(0, 12)
    ax.set_ylim(50, 90)
    ax.set_xlabel("good parts rejected (%), 162 good parts")
    ax.set_ylabel("defective parts caught (%), 238 defective")
    ax.set_title("H (seed 1216, line as built); dots: each file's own 1 % threshold")
    ax.legend(loc="lower right")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(HERE / "plan-2.png", dpi=110)


if __name__ == "__main__":
    main()
