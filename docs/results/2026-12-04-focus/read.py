"""plan.md's two readings together: the shipped file S at its stored threshold on seed 1196 through the lens at each
sigma (0: as built and 0.7 px, the ship-otherwise study's evaluations), and the edge statistic's medians from
focus-check.txt; prints a table and draws focus.png.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-04-focus/read.py > docs/results/2026-12-04-focus/read.txt
"""
import csv
import json
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

HERE = Path(__file__).parent
OTHER = HERE.parent / "2026-12-04-ship-otherwise" / "eval"
EVALS = {0.0: OTHER / "S-built", 0.7: OTHER / "S-blurff", 1.0: HERE / "eval/S-blur10", 1.5: HERE / "eval/S-blur15",
         2.0: HERE / "eval/S-blur20"}
SETS = {0.0: "so-built-1196", 0.7: "so-blurff-1196", 1.0: "fo-blur10-1196", 1.5: "fo-blur15-1196",
        2.0: "fo-blur20-1196"}
TYPES = ("chip", "dent", "missing_stud", "scratch", "stain")


def at_threshold(folder: Path) -> dict:
    rows = list(csv.DictReader(open(folder / "scores.csv")))
    y = np.array([int(r["label"]) for r in rows])
    t = np.array([r["defect_type"] for r in rows])
    rej = np.array([float(r["score"]) for r in rows]) > json.load(open(folder / "eval.json"))["threshold"]
    return {"good": int((y == 0).sum()), "good_rejected": int(rej[y == 0].sum()), "caught": float(rej[y == 1].mean()),
            **{t_: float(rej[t == t_].mean()) for t_ in TYPES}}


def main() -> None:
    text = (HERE / "focus-check.txt").read_text()
    lo, hi = (float(v) for v in re.search(r"bounds ([0-9.]+)\.\.([0-9.]+)", text).groups())
    medians = {s: float(re.search(rf"{name}\s+frames\s+\d+\s+median ([0-9.]+)", text).group(1))
               for s, name in SETS.items()}
    res = {s: at_threshold(f) for s, f in EVALS.items()}
    print("| lens blur (px) | good parts rejected | defective caught | " + " | ".join(TYPES) + " | edge_level median |")
    print("|---" * (4 + len(TYPES)) + "|")
    for s, r in res.items():
        print(f"| {s:.1f} | {r['good_rejected']} of {r['good']} | {100 * r['caught']:.1f} % | "
              + " | ".join(f"{100 * r[t]:.0f} %" for t in TYPES) + f" | {medians[s]:.4f} |")
    print(f"\ndrift monitor's edge_level bounds (the shipped file's trained range): {lo:.4f}..{hi:.4f}")
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    xs = list(res)
    a.plot(xs, [100 * res[s]["caught"] for s in xs], "o-", label="defective parts caught")
    a.plot(xs, [100 * res[s]["good_rejected"] / res[s]["good"] for s in xs], "s-", label="good parts rejected")
    a.set(xlabel="lens blur sigma (frame px)", ylabel="%", title="the shipped file, seed 1196, its threshold")
    a.legend()
    b.plot(xs, [medians[s] for s in xs], "o-", label="edge_level, median of 120 frames")
    b.axhspan(lo, hi, color="g", alpha=0.15, label="drift monitor: in range")
    b.set(xlabel="lens blur sigma (frame px)", ylabel="edge_level", title="what the drift monitor reads")
    b.legend()
    fig.tight_layout()
    fig.savefig(HERE.parent / "2026-12-04-focus.png", dpi=110)


if __name__ == "__main__":
    main()
