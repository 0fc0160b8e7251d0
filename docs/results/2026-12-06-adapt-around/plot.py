"""The figure of docs/results/2026-12-06-adapt-around.md from read.txt (run from the repository's root): per file,
the share of judged good parts rejected, of defective parts caught, and the shape check's threshold (robust z)."""

import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = Path(__file__).parent
ROW = re.compile(r"^\| (\w+) \| [\d.]+ \| (\d+) of (\d+) \| (\d+) of (\d+) ")
SHAPE = re.compile(r"^(\w+): adapted on .*?shape check refitted: .*?threshold z ([\d.]+)")
SHIPPED_SHAPE = 5.22  # the shipped file's shape check threshold (model/weights/default.json)
NAMES = {"shipped": "shipped file\n(not adapted)", "view": "adapted,\nview alone", "around": "adapted,\nframe around"}


def main() -> None:
    text = (HERE / "read.txt").read_text().splitlines()
    rows = [m.groups() for line in text if (m := ROW.match(line))]
    shape = {"shipped": SHIPPED_SHAPE, **{m[1]: float(m[2]) for line in text if (m := SHAPE.match(line))}}
    fig, axes = plt.subplots(1, 3, figsize=(10, 2.8))
    labels = [NAMES[r[0]] for r in rows]
    colours = ["tab:grey", "tab:orange", "tab:green"]
    shares = (("good parts rejected (%)", 1, 2), ("defective parts caught (%)", 3, 4))
    for ax, (title, num, den) in zip(axes[:2], shares, strict=True):
        values = [100 * int(r[num]) / int(r[den]) for r in rows]
        ax.barh(labels, values, color=colours)
        for y, (v, r) in enumerate(zip(values, rows, strict=True)):
            ax.text(v, y, f" {r[num]} of {r[den]}", va="center", fontsize=7)
        ax.set_title(title, fontsize=9)
    axes[0].set_xlim(0, 8)
    axes[1].set_xlim(0, 110)
    values = [shape[r[0]] for r in rows]
    axes[2].barh(labels, values, color=colours)
    for y, v in enumerate(values):
        axes[2].text(v, y, f" {v:.1f}", va="center", fontsize=7)
    axes[2].set_title("shape check threshold (robust z)", fontsize=9)
    axes[2].set_xlim(0, 35)
    for ax in axes:
        ax.invert_yaxis()
        ax.tick_params(labelsize=7)
    fig.suptitle("Seed 1212, camera turned 5 degrees: adapted on 200 good parts, the view alone against the frame "
                 "around it", fontsize=9)
    fig.tight_layout()
    fig.savefig(HERE.parent / "2026-12-06-adapt-around.png", dpi=110)


if __name__ == "__main__":
    main()
