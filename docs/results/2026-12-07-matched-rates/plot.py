"""The matched rates' figure, from read.txt: for each fresh set, defective parts caught by A (the shipped file) and B
(the median-pose reference) when at most 1 %, 2 % and 5 % of the set's good parts are rejected, with the bootstrap SE
of B - A as B's error bar. ``plot`` also draws plan 2's figure (../2026-12-07-blend-rates/plot.py). Run from the
repository's root; writes ../2026-12-07-matched-rates.png."""
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

ROW = re.compile(r"^\| (\d+) % \(\d+ of \d+\) \| ([\d.]+) % \| ([\d.]+) % \| [+-][\d.]+ \| ([\d.]+) \|$")


def plot(read: Path, titles: dict[str, str], labels: tuple[str, str], out: str) -> None:
    """Two panels (one per set of ``read``, a curves.py or read.py output): the first arm's caught share against the
    rate of good parts rejected, and the second's with the SE of their difference as its error bar."""
    sets: dict[str, list[tuple[int, float, float, float]]] = {}
    current = ""
    for line in read.read_text().splitlines():
        if line.startswith("== "):
            current = line.split("/")[1].split(":")[0]
            sets[current] = []
        elif m := ROW.match(line):
            sets[current].append((int(m.group(1)), *map(float, m.groups()[1:])))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for ax, (name, rows) in zip(axes, sets.items(), strict=True):
        x = [r[0] for r in rows]
        ax.plot(x, [r[1] for r in rows], marker="o", label=labels[0])
        ax.errorbar([v + 0.05 for v in x], [r[2] for r in rows], yerr=[r[3] for r in rows], marker="s", capsize=3,
                    label=labels[1])
        ax.set(xlabel="good parts rejected at most (%),\nthreshold from the set's good parts", title=titles[name],
               xticks=x)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("defective parts caught (%)")
    axes[0].legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    plot(Path("docs/results/2026-12-07-matched-rates/read.txt"),
         {"square-1236": "square camera, fresh seed 1236\n(360 good, 240 defective)",
          "turned20-1237": "camera turned +20 degrees, fresh seed 1237\n(241 good, 159 defective)"},
         ("A: the shipped file (reference from the first part)",
          "B: reference nearest the median pose (bar: SE of B - A)"), "docs/results/2026-12-07-matched-rates.png")
