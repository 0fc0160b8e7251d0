"""The study's figure: defective parts caught against good parts rejected (the threshold swept over the set's own
scores) on each set, the shipped file S against candidate L, each file's stored threshold marked.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-08-lens-train/plot.py

``plot_sets`` draws it for any such read (the smooth-field study's plot.py calls it)."""
from collections.abc import Callable
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

LABELS = {"S": "S: shipped", "L": "L: trained through a drawn lens"}


def plot_sets(load: Callable[[str, str], dict], sets: dict[str, str], labels: dict[str, str], out: Path) -> None:
    """One panel per set (``sets``: eval name -> title), one curve per model (``labels``: name -> legend), each
    file's stored threshold a dot, the threshold rule's 95 % promise (2.1 % of good parts) dashed; written to
    ``out``."""
    fig, axes = plt.subplots(1, len(sets), figsize=(11, 3.8), sharey=True)
    for ax, (name, title) in zip(axes, sets.items(), strict=True):
        for i, (m, label) in enumerate(labels.items()):
            d = load(m, name)
            good, bad = d["score"][d["label"] == 0], d["score"][d["label"] == 1]
            t = np.sort(np.concatenate([good, bad]))[::-1]
            ax.plot([100 * (good > x).mean() for x in t], [100 * (bad > x).mean() for x in t], color=f"C{i}",
                    label=label)
            ax.plot(100 * (good > d["threshold"]).mean(), 100 * (bad > d["threshold"]).mean(), "o", color=f"C{i}")
        ax.axvline(2.1, color="grey", lw=0.8, ls="--")
        ax.set_xlim(0, 12)
        ax.set_title(title.replace(": ", ":\n", 1), fontsize=9)
        ax.set_xlabel("good parts rejected (%)")
    axes[0].set_ylabel("defective parts caught (%)")
    axes[0].legend(fontsize=8, loc="lower right")
    fig.suptitle("dots: each file at its stored threshold; dashed: the threshold's 95 % promise (2.1 %)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main() -> None:
    from read import HERE, SETS, load

    plot_sets(load, SETS, LABELS, HERE.parent / "2026-12-08-lens-train.png")


if __name__ == "__main__":
    main()
