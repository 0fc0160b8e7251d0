"""five-sets.png: the two-camera station as built (rule 64's split) against the line camera alone, on its five fresh
sets. The figures are docs/second-camera.md's table (seeds 1174-1178) and this page's seed 1184, each from a
`station compare --split` report; pooled: caught and good parts rejected summed over the sets.

Usage: python plot.py (writes five-sets.png beside it)."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

# seed: (defective, line caught, pair caught, good, line good rejected, pair good rejected)
SETS = {1174: (244, 179, 197, 256, 1, 2), 1175: (235, 170, 186, 265, 5, 4), 1177: (244, 179, 198, 256, 4, 4),
        1178: (233, 174, 185, 167, 3, 2), 1184: (247, 184, 207, 153, 2, 2)}

labels = [str(s) for s in SETS] + ["pooled"]
tot = [sum(v[i] for v in SETS.values()) for i in range(6)]
rows = [*SETS.values(), tuple(tot)]
fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.8))
x = range(len(rows))
for ax, (num, den), title, unit in ((a, ((1, 2), 0), "defective parts caught", "%"),
                                    (b, ((4, 5), 3), "good parts rejected", "%")):
    for k, (name, off) in enumerate((("line camera alone", -0.2), ("both cameras, split", 0.2))):
        vals = [100 * r[num[k]] / r[den] for r in rows]
        ax.bar([i + off for i in x], vals, width=0.4, label=name)
    ax.set_xticks(list(x), labels)
    ax.set_title(title)
    ax.set_ylabel(unit)
b.axhline(1.0, color="k", lw=0.8, ls="--", label="the 1 % target")
a.set_ylim(60, 100)
a.axhline(95, color="k", lw=0.8, ls="--", label="the 95 % target")
a.legend(loc="upper left", fontsize=8)
b.legend(loc="upper right", fontsize=8)
fig.suptitle("The two-camera station as built, five fresh sets (seed 1184: +9.3 points, SE 2.0)")
fig.tight_layout()
fig.savefig(Path(__file__).with_name("five-sets.png"), dpi=110)
