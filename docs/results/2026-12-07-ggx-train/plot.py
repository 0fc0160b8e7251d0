"""The GGX screen's figure, from screen.txt: per set read before, defective parts caught (top) and good parts rejected
(bottom) by the shipped file and by the file trained with GGX lobes (G), each as the cascade C and as the blend D, at
its own 1 % threshold from the good validation parts. Run from the repository's root; writes
../2026-12-07-ggx-train.png."""
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

D = Path("docs/results/2026-12-07-ggx-train")
LINE = re.compile(r"^  (\S+) ([CD]): good rejected (\d+) of (\d+); caught (\d+) of (\d+)")
ARMS = {("model/weights/default", "C"): "shipped, C (cascade, as shipped)", ("runs/ggx-900/band-look", "C"): "G, C",
        ("model/weights/default", "D"): "shipped, D (blend)", ("runs/ggx-900/band-look", "D"): "G, D"}

sets: dict[str, dict[tuple[str, str], tuple[int, int, int, int]]] = {}
current = ""
for line in (D / "screen.txt").read_text().splitlines():
    if line.startswith("data/"):
        current = line.split("/")[1].split(":")[0]
        sets[current] = {}
    elif m := LINE.match(line):
        sets[current][(m.group(1), m.group(2))] = tuple(map(int, m.groups()[2:]))

names = list(sets)
x = np.arange(len(names))
fig, (top, bottom) = plt.subplots(2, 1, figsize=(12, 6.5), sharex=True)
for j, (arm, label) in enumerate(ARMS.items()):
    got = [sets[n][arm] for n in names]
    top.bar(x + (j - 1.5) * 0.2, [100 * c / d for _, _, c, d in got], 0.2, label=label)
    bottom.bar(x + (j - 1.5) * 0.2, [100 * r / g for r, g, _, _ in got], 0.2, label=label)
top.set(ylabel="defective parts caught (%)", ylim=(20, 95),
        title="each file at its own 1 % threshold (370 good validation parts); sets read before")
bottom.set(ylabel="good parts rejected (%)", xticks=x)
bottom.set_xticklabels(names, rotation=20, ha="right", fontsize=8)
top.legend(fontsize=8, ncol=4, loc="upper right")
for ax in (top, bottom):
    ax.grid(axis="y", alpha=0.3)
fig.tight_layout()
fig.savefig("docs/results/2026-12-07-ggx-train.png", dpi=110)
