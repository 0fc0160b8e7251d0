"""Rule 24's figure: per defect type, image AUROC and the share caught at 1 % of good parts rejected, shipped dome (D)
against dome + ring (R), on the same held-out parts; and the same scratched part under each light.

    .venv/bin/python docs/results/2026-11-27-dark-field/plot.py runs/df docs/results/2026-11-27-dark-field.png
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from sim.dataset import open_dataset


def industrial(run: Path) -> dict[str, dict]:
    return {r["type"]: r for r in json.loads((run / "eval.json").read_text())["industrial"]}


def crop(sample, margin: int = 40) -> np.ndarray:
    ys, xs = np.nonzero(sample.defect_mask)
    y0, x0 = max(ys.min() - margin, 0), max(xs.min() - margin, 0)
    return sample.s0[y0:ys.max() + margin, x0:xs.max() + margin]


def main(runs: str, out: str) -> None:
    runs_p = Path(runs)
    d, r = industrial(runs_p / "eval-D"), industrial(runs_p / "eval-R")
    types = [t for t in d if t != "all"] + ["all"]
    fig = plt.figure(figsize=(12, 7))
    for k, (key, title) in enumerate((("image_auroc", "image AUROC"), ("caught_at_1%_false_rejects",
                                                                       "caught at 1 % of good parts rejected"))):
        ax = fig.add_subplot(2, 2, k + 1)
        x = np.arange(len(types))
        ax.bar(x - 0.2, [d[t][key] for t in types], 0.4, label="D: shipped dome")
        ax.bar(x + 0.2, [r[t][key] for t in types], 0.4, label="R: half dome + low ring")
        ax.set_xticks(x, [t.replace("_", " ") for t in types], fontsize=8)
        ax.set_ylim(0 if k else 0.4, 1.0)
        ax.set_title(f"held-out parts: {title}", fontsize=9)
        ax.legend(fontsize=7)
    dd, rr = open_dataset("data/df-dome-heldout"), open_dataset("data/df-ring-heldout")
    shown = [i for i in dd.indices("test") if (dd.load(i, ground_truth=False).params.get("defect") or {}).get("type")
             == "scratch"][:4]
    for j, i in enumerate(shown):
        for c, (ds, name) in enumerate(((dd, "D"), (rr, "R"))):
            s = ds.load(i)
            ax = fig.add_subplot(4, 4, 1 + 4 * (2 + j // 2) + 2 * (j % 2) + c)
            im = crop(s)
            ax.imshow(im, cmap="gray", vmin=0, vmax=np.percentile(im, 99.5))
            ax.contour(crop_mask(s), levels=[0.5], colors="r", linewidths=0.5)
            ax.set_title(f"held-out part {i}, scratch, {name}", fontsize=8)
            ax.axis("off")
    fig.tight_layout()
    fig.savefig(out, dpi=90)


def crop_mask(sample, margin: int = 40) -> np.ndarray:
    ys, xs = np.nonzero(sample.defect_mask)
    y0, x0 = max(ys.min() - margin, 0), max(xs.min() - margin, 0)
    return sample.defect_mask[y0:ys.max() + margin, x0:xs.max() + margin].astype(float)


if __name__ == "__main__":
    main(*sys.argv[1:3])
