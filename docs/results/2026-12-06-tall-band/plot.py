"""The tall band's screen as a figure (read.txt -> ../2026-12-06-tall-band.png): per set, good parts rejected and
defective parts caught by each arm. Run from the repository's root."""

import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = Path(__file__).parent
LINE = re.compile(r"^data/([\w-]+):\w+ ([BT]): (\d+) of (\d+) good rejected; (\d+) of (\d+) defective")
rows: dict[str, dict[str, tuple[int, ...]]] = {}
for line in (HERE / "read.txt").read_text().splitlines():
    if m := LINE.match(line):
        rows.setdefault(m[1], {})[m[2]] = tuple(int(g) for g in m.groups()[2:])
sets = list(rows)
fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
PANELS = (("good parts rejected (%)", 0, 1), ("defective parts caught (%)", 2, 3))
for ax, (what, i, j) in zip(axes, PANELS, strict=True):
    for k, (arm, colour) in enumerate((("B", "tab:grey"), ("T", "tab:blue"))):
        share = [100 * rows[s][arm][i] / rows[s][arm][j] for s in sets]
        ax.bar([n + (k - 0.5) * 0.38 for n in range(len(sets))], share, 0.38, color=colour,
               label={"B": "B: band, 96 x 192", "T": "T: tall, 128 x 192"}[arm])
    ax.set_xticks(range(len(sets)), [s.replace("line-", "") for s in sets], rotation=40, ha="right", fontsize=8)
    ax.set_ylabel(what)
    ax.grid(axis="y", alpha=0.3)
axes[0].legend()
fig.suptitle("Variation-only files, threshold at 1 % of line-pv-val's good parts (a screen on sets read before)")
fig.tight_layout()
fig.savefig(HERE.parent / "2026-12-06-tall-band.png", dpi=90)
