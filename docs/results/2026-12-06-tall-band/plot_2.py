"""Plan 2's reading as a figure (read-2.txt -> ../2026-12-06-tall-band-recipe.png): defective parts caught per kind
by the shipped file and the tall file on the same 400 fresh parts. Run from the repository's root."""

import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = Path(__file__).parent
LINE = re.compile(r"^data/[\w-]+:\w+ ([BT]): .*defective caught \(([\d.]+) %; (.*)\); parts")
caught: dict[str, dict[str, float]] = {}
for line in (HERE / "read-2.txt").read_text().splitlines():
    if m := LINE.match(line):
        kinds = {k: int(a) / int(n) for k, a, n in re.findall(r"(\w+) (\d+)/(\d+)", m[3])}
        caught[m[1]] = {"all": float(m[2]) / 100, **kinds}
names = list(caught["B"])
fig, ax = plt.subplots(figsize=(8, 4))
for k, (arm, colour, label) in enumerate((("B", "tab:grey", "shipped: band, 96 x 192"),
                                          ("T", "tab:blue", "tall, 128 x 192"))):
    ax.bar([n + (k - 0.5) * 0.38 for n in range(len(names))], [100 * caught[arm][c] for c in names], 0.38,
           color=colour, label=label)
ax.set_xticks(range(len(names)), [c.replace("_", " ") for c in names])
ax.set_ylabel("defective parts caught (%)")
ax.grid(axis="y", alpha=0.3)
ax.legend()
ax.set_title("Seed 1209, 400 fresh parts, square; each file's threshold at 1 % of line-pv-val's good parts",
             fontsize=9)
fig.tight_layout()
fig.savefig(HERE.parent / "2026-12-06-tall-band-recipe.png", dpi=90)
