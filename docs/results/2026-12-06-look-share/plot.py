"""The figure of docs/results/2026-12-06-look-share.md from look_share.txt (run from the repository's root): per kind,
the share of defective parts caught by the shipped file and by its window alone, each at its own 1 % threshold."""

import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = Path(__file__).parent
ROW = re.compile(r"^\s+(\S+)\s+(\d+): file\s+(\d+) \(\s*([\d.]+) %\), window alone\s+(\d+) \(\s*([\d.]+) %\)")
SET = re.compile(r"^data/(\S+):test:")


def main() -> None:
    rows, name = [], ""
    for line in (HERE / "look_share.txt").read_text().splitlines():
        if m := SET.match(line):
            name = "new kinds, seed 1195" if "new-kinds" in m.group(1) else "five kinds, seed 1194"
        elif m := ROW.match(line):
            rows.append((f"{m.group(1)} ({name})", float(m.group(4)), float(m.group(6))))
    fig, ax = plt.subplots(figsize=(7, 4))
    y = range(len(rows))
    ax.barh([i - 0.2 for i in y], [r[1] for r in rows], height=0.4, color="tab:green",
            label="shipped file (window + look)")
    ax.barh([i + 0.2 for i in y], [r[2] for r in rows], height=0.4, color="tab:grey", label="window alone")
    ax.set_yticks(list(y), [r[0] for r in rows], fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("defective parts caught at 1 % of good validation parts rejected (%)", fontsize=8)
    ax.legend(fontsize=7)
    ax.tick_params(labelsize=7)
    fig.tight_layout()
    fig.savefig(HERE.parent / "2026-12-06-look-share.png", dpi=110)


if __name__ == "__main__":
    main()
