"""Plan 68's figure: good parts rejected by each file on each set of seed 1188, beside plan 68's bar (table.json).

    python plot.py   (writes ../2026-12-02-rendered-otherwise.png)"""
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

here = Path(__file__).parent
t = json.loads((here / "table.json").read_text())
sets = (("as built", "line-panel-heldout-1188"), ("GGX lobe", "om-ggx-1188"), ("duller plastic", "om-rough-1188"),
        ("panel at half", "pb-half-1188"), ("lens blur 0.7 px", "so-blurff-1188"),
        ("five imperfections", "so-allff-1188"))
x = np.arange(len(sets))
fig, ax = plt.subplots(figsize=(8, 3.6))
for k, (f, label) in enumerate((("E63", "shipped file (E63)"), ("F63", "the file before (F63)"))):
    share = [100 * t[f"{f}/{d}"]["good_rejected"] / t[f"{f}/{d}"]["good"] for _, d in sets]
    ax.bar(x + (k - 0.5) * 0.38, share, 0.38, label=label)
ax.axhline(3.2, color="k", ls="--", lw=1, label="plan 68's bar (3.2 %)")
ax.set_xticks(x, [name for name, _ in sets], fontsize=8)
ax.set_ylabel("good parts rejected (%)")
ax.set_title("Seed 1188 (165 good parts), each file at its own threshold", fontsize=9)
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(here.parent / "2026-12-02-rendered-otherwise.png", dpi=110)
