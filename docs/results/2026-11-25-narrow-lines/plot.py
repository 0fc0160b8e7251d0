"""The plot of docs/results/2026-11-25-narrow-lines.md: per narrowed line, image, dent and scratch AUROC of a
variation model fitted on 210 of its good parts and of the shipped model.

    .venv/bin/python docs/results/2026-11-25-narrow-lines/plot.py
"""
from __future__ import annotations

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = Path(__file__).parent
LINES = [("camera fixed", HERE.parent / "2026-11-24-fixed-camera/fixed.json"),
         ("one material", HERE.parent / "2026-11-24-fixed-material/fixed.json"),
         ("pose fixed", HERE.parent / "2026-11-24-fixed-pose/fixed.json"),
         ("no stray light", HERE / "no-stray.json"),
         ("exposure, gain fixed", HERE / "fixed-exposure.json"),
         ("camera, stray light,\nexposure fixed", HERE / "controlled.json"),
         ("material, pose fixed", HERE / "parts-fixed.json"),
         ("all five fixed", HERE / "all-fixed.json"),
         ("light on camera side", HERE / "camera-side.json")]
COLUMNS = (("auroc", "image"), ("dent", "dent"), ("scratch", "scratch"))


def main() -> None:
    fig, axes = plt.subplots(1, len(COLUMNS), figsize=(13, 4.2), sharey=True)
    present = [(n, p) for n, p in LINES if p.exists()]
    for ax, (key, title) in zip(axes, COLUMNS, strict=True):
        for k, (_, path) in enumerate(present):
            rows = json.loads(path.read_text())
            fit = next(v for r, v in rows.items() if "fit" in r)
            ax.barh(k + 0.2, fit[key], 0.4, color="tab:blue", label="fit on 210 of its parts" if k == 0 else None)
            ax.barh(k - 0.2, rows["shipped"][key], 0.4, color="tab:grey", label="shipped model" if k == 0 else None)
        ax.axvline(0.853 if key == "auroc" else 0.782 if key == "dent" else 0.590, color="k", ls=":", lw=1)
        ax.set_title(f"{title} AUROC (dotted: the broad line)")
        ax.set_xlim(0.4, 1.0)
        ax.set_yticks(range(len(present)), [n for n, _ in present])
    fig.legend(*axes[0].get_legend_handles_labels(), loc="lower center", ncol=2, fontsize=9)
    fig.suptitle("Held-out parts of each narrowed line (16 spp, thresholds and fits on its own good parts)")
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    fig.savefig(HERE.parent / "2026-11-25-narrow-lines.png", dpi=110)


if __name__ == "__main__":
    main()
