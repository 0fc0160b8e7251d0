"""One figure for the page: every candidate's validation gain over the shipped statistic (caught at 1 % of good
parts rejected, and image AUROC), with one paired-bootstrap SE either side.

Usage: plot.py OUT.png RULE=JSON ..., from the repository root (the JSONs of knn.py, highpass.py, localpca.py and
evaluate.py)."""

from __future__ import annotations

import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = []
for arg in sys.argv[2:]:
    rule, path = arg.split("=", 1)
    for name, r in json.load(open(path))["validation"].items():
        if name != "shipped":
            rows.append((f"{rule}: {name}", r))
fig, axes = plt.subplots(1, 2, figsize=(10, 0.35 * len(rows) + 1.2), sharey=True)
for ax, (key, title) in zip(
    axes, (("c1", "caught at 1 % of good parts rejected"), ("auc", "image AUROC")), strict=True
):
    y = range(len(rows))
    ax.errorbar([r[f"d_{key}"] for _, r in rows], y, xerr=[r[f"se_{key}"] for _, r in rows], fmt="o", capsize=3)
    ax.axvline(0, color="grey", lw=1)
    ax.set_title(f"gain over the shipped statistic: {title}", fontsize=9)
    ax.set_yticks(list(y), [n for n, _ in rows], fontsize=8)
    ax.invert_yaxis()
fig.suptitle("Validation set (600 parts, seed 303); bars: one paired-bootstrap SE", fontsize=9)
fig.tight_layout()
fig.savefig(sys.argv[1], dpi=110)
