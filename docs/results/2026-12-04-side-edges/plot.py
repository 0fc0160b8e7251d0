"""side-edges.png: the two-camera station with make side-model's edge-range file on seed 1192, as built, with every
edge chamfered 0.3 mm, and rounded 0.3 mm (the addendum): defective parts caught and good parts rejected by each rule
of `station compare --split` (two-cameras-1192.json, -e3.json and -r3.json beside this file).

Usage: python plot.py (writes side-edges.png beside it)."""
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = Path(__file__).parent
SETS = {"as built": "two-cameras-1192.json", "chamfered\n0.3 mm": "two-cameras-1192-e3.json",
        "rounded 0.3 mm\n(no chips)": "two-cameras-1192-r3.json"}
RULES = ("line camera alone", "side camera alone", "both, split")

reports = {name: json.loads((HERE / f).read_text())["rules"] for name, f in SETS.items()}
fig, axes = plt.subplots(1, 2, figsize=(12, 3.8))
for ax, (num, den, title) in zip(axes, (("caught", "defective", "defective parts caught"),
                                        ("good_rejected", "good", "good parts rejected")), strict=True):
    for k, rule in enumerate(RULES):
        vals = [100 * rows[k][num] / max(rows[k][den], 1) for rows in reports.values()]
        bars = ax.bar([i + 0.27 * (k - 1) for i in range(len(SETS))], vals, width=0.27, label=rule)
        ax.bar_label(bars, fmt="%.1f", fontsize=7)
    ax.set_xticks(range(len(SETS)), list(SETS))
    ax.set_title(title)
    ax.set_ylabel("%")
axes[0].set_ylim(0, 115)
axes[0].legend(loc="upper center", ncol=3, fontsize=8)
axes[1].axhline(1.0, color="k", lw=0.8, ls="--")
fig.suptitle("Seed 1192, make side-model with edges drawn 0-0.4 mm (thresholds from validation, held fixed)")
fig.tight_layout()
fig.savefig(HERE / "side-edges.png", dpi=110)
