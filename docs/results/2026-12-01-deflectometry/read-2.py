"""plan-2.md's reading: RAD alone at the line's 1 % (its 1 % point on `line-pv-val`, as tilt-apart's read.py takes
it) against RADF at its own 1 % point on its validation set, on the same parts of seed 1176: good parts rejected,
defective caught (all, per type, top-face dents and scratches), and the caught difference's paired bootstrap SE
(2000 resamples over parts). Thresholds are read from each report's eval.md.

Usage: python read-2.py RAD_EVAL RADF_EVAL [LABEL [NAME_A NAME_B]]  (LABEL: the table's first header, "seed 1176"
unless given; NAME_A, NAME_B: the rows' names, "RAD alone, the line's 1 %" and "RADF, its 1 %" unless given)"""
import csv
import re
import sys

import numpy as np


def report(folder):
    """A ``station eval`` report's 1 % threshold (from its eval.md) and its parts' scores.csv rows by index."""
    text = open(f"{folder}/eval.md").read()
    threshold = float(re.search(r"1 % -> ([0-9.]+)", text).group(1))
    rows = list(csv.DictReader(open(f"{folder}/scores.csv")))
    return threshold, {int(r["index"]): r for r in rows}


if __name__ == "__main__":
    (t_a, a), (t_b, b) = report(sys.argv[1]), report(sys.argv[2])
    idx = sorted(set(a) & set(b))
    label = np.array([int(a[i]["label"]) for i in idx])
    kind = np.array([a[i]["defect_type"] for i in idx])
    face = np.array([a[i]["face"] for i in idx])
    ca = np.array([float(a[i]["score"]) > t_a for i in idx])
    cb = np.array([float(b[i]["score"]) > t_b for i in idx])
    good, bad = label == 0, label == 1
    label_text = sys.argv[3] if len(sys.argv) > 3 else "seed 1176"
    print(f"| {label_text} (threshold) | good parts rejected | caught | "
          + " | ".join(sorted(set(kind[bad]))) + " | top-face dents | top-face scratches |")
    print("|---" * (5 + len(set(kind[bad]))) + "|")
    names = sys.argv[4:6] if len(sys.argv) > 5 else ["RAD alone, the line's 1 %", "RADF, its 1 %"]
    for name, t, c in ((names[0], t_a, ca), (names[1], t_b, cb)):
        per = [f"{100 * c[bad & (kind == k)].mean():.0f} %" for k in sorted(set(kind[bad]))]
        on_top = [bad & (kind == k) & (face == "top") for k in ("dent", "scratch")]
        top = [f"{100 * c[m].mean():.0f} % of {m.sum()}" for m in on_top]
        print(f"| {name} ({t:.4f}) | {100 * c[good].mean():.1f} % ({c[good].sum()} of {good.sum()}) | "
              f"{100 * c[bad].mean():.1f} % | " + " | ".join(per + top) + " |")
    rng = np.random.default_rng(0)
    d = (cb[bad].astype(float) - ca[bad].astype(float))
    boots = [d[rng.integers(0, d.size, d.size)].mean() for _ in range(2000)]
    short = [n.split(",")[0] for n in names]  # "RAD alone", "RADF" by default
    print(f"{short[1]} minus {short[0]}, defective caught: {100 * d.mean():+.1f} points (paired bootstrap SE "
          f"{100 * np.std(boots):.1f})")
