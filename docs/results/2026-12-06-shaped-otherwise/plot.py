"""The figure of docs/results/2026-12-06-shaped-otherwise.md (run from the repository's root): per kind, defective parts
caught by the shipped file and by its window alone at their 1 % thresholds, on seed 1194 (the kinds as the training
draws them) and seed 1220 (shaped otherwise), from the two look_share.txt readings."""

import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = Path(__file__).parent
READS = {"seed 1194, as drawn": HERE.parent / "2026-12-06-look-share" / "look_share.txt",
         "seed 1220, shaped otherwise": HERE / "look_share.txt"}
SET = re.compile(r"^data/(\S+):test:")
ROW = re.compile(r"^\s+(\S+)\s+(\d+): file\s+(\d+) \(\s*([\d.]+) %\), window alone\s+(\d+) \(\s*([\d.]+) %\)")


def rows(path: Path, wanted: str) -> dict[str, tuple[float, float]]:
    """kind -> (caught by the file, by the window alone) in % for the set whose folder contains ``wanted``."""
    out, on = {}, False
    for line in path.read_text().splitlines():
        if m := SET.match(line):
            on = wanted in m.group(1)
        elif on and (m := ROW.match(line)):
            out[m.group(1)] = (float(m.group(4)), float(m.group(6)))
    return out


def main() -> None:
    got = {name: rows(path, "1194" if "1194" in name else "1220") for name, path in READS.items()}
    kinds = list(next(iter(got.values())))
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.7), sharey=True)
    for ax, (name, per) in zip(axes, got.items(), strict=True):
        y = range(len(kinds))
        ax.barh([i - 0.2 for i in y], [per[k][0] for k in kinds], height=0.4, color="tab:green",
                label="shipped file (window + look)")
        ax.barh([i + 0.2 for i in y], [per[k][1] for k in kinds], height=0.4, color="tab:grey", label="window alone")
        ax.set_yticks(list(y), kinds, fontsize=7)
        ax.set_title(name, fontsize=9)
        ax.set_xlim(0, 100)
        ax.set_xlabel("caught at 1 % of good validation parts rejected (%)", fontsize=7)
        ax.tick_params(labelsize=7)
    axes[0].invert_yaxis()
    fig.legend(*axes[0].get_legend_handles_labels(), fontsize=7, loc="lower center", ncol=2)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    fig.savefig(HERE.parent / "2026-12-06-shaped-otherwise.png", dpi=110)


if __name__ == "__main__":
    main()
