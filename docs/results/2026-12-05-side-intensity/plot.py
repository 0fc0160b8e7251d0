"""The figure: each pair's share of defective parts caught and of good parts rejected, SA against SI, as built and
rendered otherwise, and the addenda's sets (read.json).

    cd docs/results/2026-12-05-side-intensity && ../../../.venv/bin/python plot.py
"""
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = Path(__file__).parent
read = json.loads((HERE / "read.json").read_text())
groups = list(read)
fig, axes = plt.subplots(2, 1, figsize=(9, 6.4))
for ax, (key, total, label) in zip(axes, (("caught", "defective", "defective parts caught (%)"),
                                          ("good_rejected", "good", "good parts rejected (%)")), strict=True):
    for j, side in enumerate(("SA", "SI")):
        values = [100 * read[g][side][key] / read[g][side][total] for g in groups]
        bars = ax.bar([k + (j - 0.5) * 0.38 for k in range(len(groups))], values, 0.38,
                      label={"SA": "side file with DoLP and AoLP (SA)", "SI": "side file, intensity alone (SI)"}[side])
        ax.bar_label(bars, [f"{read[g][side][key]} of {read[g][side][total]}" for g in groups], fontsize=7)
    ax.set_xticks(range(len(groups)), [g.replace(" (", "\n(").replace("; ", "\n") for g in groups], fontsize=8)
    ax.set(ylabel=label)
axes[0].set_ylim(0, 100)
axes[1].set_ylim(0, 3)
axes[0].legend(fontsize=7, loc="lower left")
fig.suptitle("the two cameras at each side file's split with the shipped line file, held-out renders", fontsize=9)
fig.tight_layout()
fig.savefig(HERE.parent / "2026-12-05-side-intensity.png", dpi=110)
