"""The recipe's training time by step against issue 19's 3 h, from the two studies' timings (wall seconds):
../2026-12-03-recipe-time/timings.tsv (fit, looks) and timings.tsv here (networks). Writes recipe-time.png.
Run from this folder: ../../../.venv/bin/python plot.py"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = Path(__file__).parent


def seconds(path: Path) -> dict[str, int]:
    """Each step's wall seconds, summed over a rerun's lines."""
    out: dict[str, int] = {}
    for line in path.read_text().splitlines():
        name, secs, _ = line.split("\t")
        out[name] = out.get(name, 0) + int(secs)
    return out


nets = seconds(HERE / "timings.tsv")
fit = seconds(HERE.parent / "2026-12-03-recipe-time" / "timings.tsv")
# make model's six looks (shipped + five held-out types) run two at a time: three rounds of a pair's wall time
steps = [("base", nets["base"]), ("mixed", nets["mixed"]), ("band", nets["band"]), ("fit", fit["variation"]),
         ("6 looks, 2 at a time", 3 * fit["holdout-pair"])]
minutes = [s / 60 for _, s in steps]
fig, ax = plt.subplots(figsize=(7, 2.6))
ax.set_ylim(-0.5, 0.9)
left = 0.0
for (name, _), m in zip(steps, minutes, strict=True):
    ax.barh(0, m, left=left, edgecolor="white")
    narrow = m < 5  # its label above the bar
    ax.text(left + m / 2, 0.5 if narrow else 0, f"{name}\n{m:.0f} min", ha="center",
            va="bottom" if narrow else "center", fontsize=8)
    left += m
ax.axvline(180, color="red", linestyle="--")
ax.text(178, 0.3, "issue 19: 3 h", color="red", ha="right", fontsize=8)
ax.set_xlim(0, 190)
ax.set_yticks([])
ax.set_xlabel(f"make model's training on 2 cores, minutes (total {left:.0f}; renders not counted)")
fig.tight_layout()
fig.savefig(HERE / "recipe-time.png", dpi=120)
print(f"total {left:.1f} min")
