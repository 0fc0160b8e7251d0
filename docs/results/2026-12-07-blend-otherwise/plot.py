"""The study's figure: good parts rejected and defective parts caught per rendering, the shipped blend S against its
cascade C, each at its stored threshold (read.json).

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-07-blend-otherwise/plot.py
"""
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

HERE = Path(__file__).parent
NAMES = {"built": "as built", "ggx": "GGX", "rough": "duller\nplastic", "half": "panel\nat half",
         "motion2": "moving\n2 px", "motion4": "moving\n4 px", "pedestal256": "pedestal\n256",
         "camera": "sensor\npatterns", "hot30": "30 hot\npixels", "blurff": "lens blur\n0.7 px",
         "allff": "blur and\nimperfections"}
PROMISE = 2.1  # plan.md: the 95 % promise of a 1 % threshold on 370 good validation parts, in %


def main() -> None:
    r = json.loads((HERE / "read.json").read_text())
    names = [k for k in NAMES if k in r]
    x = np.arange(len(names))
    fig, ax = plt.subplots(2, 1, figsize=(9.5, 5.6), sharex=True)
    for i, (m, label) in enumerate((("S", "S: shipped, the blend"), ("C", "C: the same file's cascade"))):
        ax[0].bar(x + (i - 0.5) * 0.38, [100 * r[k][m]["good_rejected"] / r[k]["good"] for k in names], 0.38,
                  label=label)
        ax[1].bar(x + (i - 0.5) * 0.38, [100 * r[k][m]["caught"] for k in names], 0.38, label=label)
    ax[0].set_ylabel("good parts rejected (%)")
    ax[1].set_ylabel("defective parts caught (%)")
    ax[1].set_xticks(x, [NAMES[k] for k in names], fontsize=8)
    ax[0].axhline(PROMISE, color="grey", lw=0.8, ls="--", label="the threshold's 95 % promise")
    ax[1].set_ylim(40, 100)
    ax[0].legend(fontsize=8)
    fig.suptitle(f"fresh seed 1240, each file at its stored threshold ({r['built']['good']} good parts as built)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(HERE.parent / "2026-12-07-blend-otherwise.png", dpi=110)


if __name__ == "__main__":
    main()
