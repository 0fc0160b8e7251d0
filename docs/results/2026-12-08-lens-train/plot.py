"""The study's figure: defective parts caught against good parts rejected (the threshold swept over the set's own
scores) on each set, the shipped file S against candidate L, each file's stored threshold marked.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-08-lens-train/plot.py
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from read import HERE, MODELS, SETS, load

LABELS = {"S": "S: shipped", "L": "L: trained through a drawn lens"}


def main() -> None:
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.8), sharey=True)
    for ax, (name, title) in zip(axes, SETS.items(), strict=True):
        for m, colour in zip(MODELS, ("C0", "C1"), strict=True):
            d = load(m, name)
            good, bad = d["score"][d["label"] == 0], d["score"][d["label"] == 1]
            t = np.sort(np.concatenate([good, bad]))[::-1]
            ax.plot([100 * (good > x).mean() for x in t], [100 * (bad > x).mean() for x in t], color=colour,
                    label=LABELS[m])
            ax.plot(100 * (good > d["threshold"]).mean(), 100 * (bad > d["threshold"]).mean(), "o", color=colour)
        ax.axvline(2.1, color="grey", lw=0.8, ls="--")
        ax.set_xlim(0, 12)
        ax.set_title(title.replace(": ", ":\n", 1), fontsize=9)
        ax.set_xlabel("good parts rejected (%)")
    axes[0].set_ylabel("defective parts caught (%)")
    axes[0].legend(fontsize=8, loc="lower right")
    fig.suptitle("dots: each file at its stored threshold; dashed: the threshold's 95 % promise (2.1 %)", fontsize=9)
    fig.tight_layout()
    fig.savefig(HERE.parent / "2026-12-08-lens-train.png", dpi=110)


if __name__ == "__main__":
    main()
