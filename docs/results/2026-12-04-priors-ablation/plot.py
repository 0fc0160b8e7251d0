"""The priors ablation's figure: image AUROC per defect type and defective parts caught at 2 and 8 of each set's good
parts rejected, both seeds pooled, for R, RA and RAD (matched.py's measures).

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-04-priors-ablation/plot.py
"""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from matched import MODELS, SEEDS, pooled, read

from model.draem.metrics import auroc

HERE = Path(__file__).parent
NAMES = {"R": "R: intensity", "RA": "RA: + AoLP", "RAD": "RAD: + DoLP (shipped)"}


def main() -> None:
    data = {(m, s): read(m, s) for m in MODELS for s in SEEDS}
    y = np.concatenate([data["RAD", s][0] for s in SEEDS])
    types = np.concatenate([data["RAD", s][2] for s in SEEDS])
    kinds = ["all", *sorted(set(types) - {""})]
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.2), gridspec_kw={"width_ratios": [3, 1.3]})
    width = 0.8 / len(MODELS)
    for j, m in enumerate(MODELS):
        score = np.concatenate([data[m, s][1] for s in SEEDS])
        values = []
        for t in kinds:
            keep = np.ones(y.size, bool) if t == "all" else (types == t) | (y == 0)
            values.append(auroc(y[keep], score[keep]))
        left.bar(np.arange(len(kinds)) + (j - 1) * width, values, width, label=NAMES[m])
        n_good = {s: int((data[m, s][0] == 0).sum()) for s in SEEDS}
        caught = [pooled([data[m, s][:2] for s in SEEDS], [k / n_good[s] for s in SEEDS]) for k in (2, 8)]
        right.bar(np.arange(2) + (j - 1) * width, 100 * np.array(caught), width, label=NAMES[m])
    left.set_xticks(range(len(kinds)), [k.replace("_", " ") for k in kinds])
    left.set_ylim(0.5, 1.0)
    left.set_ylabel("image AUROC (seeds 1191 + 1192)")
    right.set_xticks(range(2), ["2 good rejected\nper set (~1.2 %)", "8 per set (~5 %)"])
    right.set_ylim(0, 100)
    right.set_ylabel("defective parts caught, %")
    fig.suptitle("The paper's priors ablation on the shipped recipe (variation model + look network)")
    handles, labels = left.get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", ncol=3, bbox_to_anchor=(0.5, 0.93), fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 0.86))
    fig.savefig(HERE.parent / "2026-12-04-priors-ablation.png", dpi=110)


if __name__ == "__main__":
    main()
