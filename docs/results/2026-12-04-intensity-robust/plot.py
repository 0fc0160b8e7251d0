"""The study's figure: good parts rejected and defective parts caught per rendering, R against E63 (read.json).

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-04-intensity-robust/plot.py
"""
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

HERE = Path(__file__).parent
NAMES = {"built": "as built", "ggx": "GGX lobe", "rough": "duller plastic"}


def main() -> None:
    r = json.loads((HERE / "read.json").read_text())
    x = np.arange(len(NAMES))
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.4))
    for i, m in enumerate(("R", "E63")):
        label = "R: intensity alone" if m == "R" else "E63: shipped (intensity, DoLP, AoLP)"
        ax[0].bar(x + (i - 0.5) * 0.38, [100 * r[k][m]["good_rejected"] / r[k]["good"] for k in NAMES], 0.38,
                  label=label)
        ax[1].bar(x + (i - 0.5) * 0.38, [100 * r[k][m]["caught"] for k in NAMES], 0.38, label=label)
    ax[0].set_ylabel("good parts rejected (%)")
    ax[1].set_ylabel("defective parts caught (%)")
    for a in ax:
        a.set_xticks(x, list(NAMES.values()))
    ax[0].axhline(1, color="grey", lw=0.8, ls="--")
    ax[1].set_ylim(50, 100)
    ax[0].legend(fontsize=8)
    fig.suptitle(f"seed 1193, each file at its stored threshold ({r['built']['good']} good parts)", fontsize=10)
    fig.tight_layout()
    fig.savefig(HERE.parent / "2026-12-04-intensity-robust.png", dpi=110)


if __name__ == "__main__":
    main()
