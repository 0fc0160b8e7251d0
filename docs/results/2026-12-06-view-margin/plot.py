"""The figure of docs/results/2026-12-06-view-margin.md from read-T.txt and read-S.txt (run from the repository's
root): per set and arm, the share of good parts rejected and of defective parts caught at the shipped threshold."""

import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = Path(__file__).parent
LINE = re.compile(r"^(\S+):test (before|around): (\d+) of (\d+) good rejected .*?; (\d+) of (\d+) defective caught")
NAMES = {"data/margin-1211-turned5": "T: turned 5 degrees (200 parts)", "data/margin-1211": "S: square (400 parts)"}


def main() -> None:
    rows = [m.groups() for f in ("read-T.txt", "read-S.txt") for line in (HERE / f).read_text().splitlines()
            if (m := LINE.match(line))]
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.2))
    for ax, (title, num, den) in zip(axes, (("good parts rejected (%)", 2, 3), ("defective parts caught (%)", 4, 5)),
                                     strict=True):
        labels = [f"{NAMES[r[0]]}\n{'frame around' if r[1] == 'around' else 'view alone'}" for r in rows]
        values = [100 * int(r[num]) / int(r[den]) for r in rows]
        colours = ["tab:green" if r[1] == "around" else "tab:grey" for r in rows]
        ax.barh(labels, values, color=colours)
        for y, (v, r) in enumerate(zip(values, rows, strict=True)):
            ax.text(v, y, f" {r[num]} of {r[den]}", va="center", fontsize=7)
        ax.set_title(title, fontsize=9)
        ax.invert_yaxis()
        ax.tick_params(labelsize=7)
    axes[1].set_xlim(0, 100)
    axes[0].set_xlim(0, 6)
    fig.suptitle("Shipped file, seed 1211, at its threshold: the view alone against the frame around it", fontsize=9)
    fig.tight_layout()
    fig.savefig(HERE.parent / "2026-12-06-view-margin.png", dpi=110)


if __name__ == "__main__":
    main()
