"""Rule 69's figure from decide69.json: good parts rejected on each rendering of seed 1190 (left, with the rule's
3.2 % bar for G and R) and defective parts caught per type on the line as built (right), E63 beside L63, each at its
own threshold.

    python plot.py   (writes ../2026-12-02-lobe-fit.png)"""
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

here = Path(__file__).parent
d = json.loads((here / "decide69.json").read_text())
sets = (("S", "as built"), ("G", "GGX lobe"), ("R", "duller plastic"))
files = (("A", "shipped file (E63)"), ("B", "candidate (L63)"))
fig, (left, right) = plt.subplots(1, 2, figsize=(10, 3.6), gridspec_kw={"width_ratios": [1, 1.6]})
x = np.arange(len(sets))
for k, (who, label) in enumerate(files):
    share = [100 * d[s][who]["good_rejected"] / d[s][who]["good"] for s, _ in sets]
    left.bar(x + (k - 0.5) * 0.38, share, 0.38, label=label)
left.axhline(3.2, color="k", ls="--", lw=1, label="rule 69's bar for G and R (3.2 %)")
left.set_xticks(x, [name for _, name in sets], fontsize=8)
left.set_ylabel("good parts rejected (%)")
left.set_title(f"Seed 1190 ({d['S']['A']['good']} good parts)", fontsize=9)
left.legend(fontsize=7)
types = d["S"]["caught_by_type"]
x = np.arange(len(types))
for k, (_, label) in enumerate(files):
    right.bar(x + (k - 0.5) * 0.38, [100 * v[k] for v in types.values()], 0.38, label=label)
right.set_xticks(x, [f"{t}\n({v[2]})" for t, v in types.items()], fontsize=8)
right.set_ylabel("defective parts caught (%)")
right.set_ylim(0, 100)
right.set_title("As built, per type (parts)", fontsize=9)
right.legend(fontsize=7)
fig.tight_layout()
fig.savefig(here.parent / "2026-12-02-lobe-fit.png", dpi=110)
