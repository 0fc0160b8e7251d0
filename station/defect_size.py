"""Detection by defect size: a detector's image-level results per defect type, split into thirds by a size, so a
line can state which defects of a type it catches, not only how many. Two sizes (``MEASURES``): the physical one
that governs each type's visibility (``sim.defects.defect_size``: a dent's steepest tilt, a scratch's area, a
stain's radius, a chip's cut, a blister's tilt, a particle's radius; missing studs are all alike) and the apparent
one, the defect's pixels in the frame (``sim.defects.apparent_size``), which also says how squarely its face is
seen and how much of it is hidden.

Rows per size and type: each third of that type's defects in the split, by size (equal counts), with the size
range, the defects, the share caught (image score > the threshold, as ``station eval``'s ``detected``) and the image
AUROC of those defects against every good part.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from sim.defects import apparent_size, defect_size

COLUMNS = ["type", "size", "range", "defects", "caught", "image_auroc"]
PARTS = 3
"""Size bins per type: thirds (with about 45 defects of a type in a 400-part set, 15 a bin)."""
MEASURES = (defect_size, apparent_size)
"""The sizes reported, each a function of a ``params.json`` defect record: (name, value) or None."""


def by_size(records: Sequence[dict | None], labels: Sequence[int], scores: Sequence[float],
            threshold: float | None, types: Sequence[str]) -> list[dict]:
    """``detection_by_size`` for each of ``MEASURES``, from the samples' defect records
    (``sim.dataset.defect_records``)."""
    return [row for measure in MEASURES
            for row in detection_by_size(labels, scores, threshold, [measure(d) for d in records], types)]


def detection_by_size(labels: Sequence[int], scores: Sequence[float], threshold: float | None,
                      sizes: Sequence[tuple[str, float] | None], types: Sequence[str]) -> list[dict]:
    """Rows (``COLUMNS``) per type and third of its defects by size; empty when no defect has a size. ``caught`` is
    NaN without a threshold, ``image_auroc`` NaN without good parts. The range is "lo-hi" in the size's unit
    (``size`` names it)."""
    from model.draem.metrics import auroc

    y = np.asarray(labels, bool)
    s = np.asarray(scores, np.float64)
    known = {i: z for i, z in enumerate(sizes) if y[i] and z is not None}  # position -> (size name, value)
    rows = []
    for typ in sorted({str(types[i]) for i in known}):
        order = sorted((i for i in known if types[i] == typ), key=lambda i: known[i][1])
        for part in np.array_split(np.array(order), min(PARTS, len(order))):
            sel = np.zeros(len(y), bool)
            sel[part] = True
            vals = [known[i][1] for i in part]
            caught = float(np.mean(s[sel] > threshold)) if threshold is not None else math.nan
            both = sel | ~y
            roc = auroc(y[both], s[both]) if (~y).any() else math.nan
            rows.append({"type": typ, "size": known[int(part[0])][0], "range": f"{_num(min(vals))}-{_num(max(vals))}",
                         "defects": int(sel.sum()), "caught": caught, "image_auroc": float(roc)})
    return rows


def _num(v: float) -> str:
    """A size as a range bound: 3 significant digits, whole numbers from 1000 up (pixels: 1840, not 1.84e+03)."""
    return f"{v:.3g}" if abs(v) < 1000 else f"{v:.0f}"


def plot(out: Path, rows: list[dict]) -> str:
    """Bars per type, one per third by size (smallest first), of the share caught; returns the file name."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    groups = list(dict.fromkeys((r["size"], r["type"]) for r in rows))
    fig, ax = plt.subplots(figsize=(1.0 + 0.75 * len(groups), 3.2))
    width = 0.8 / PARTS
    for k, group in enumerate(groups):
        mine = [r for r in rows if (r["size"], r["type"]) == group]
        for j, r in enumerate(mine):
            x = k - 0.4 + width * (j + 0.5)
            ax.bar(x, r["caught"], width * 0.9, color=f"C{j}")
            ax.text(x, 0.01, r["range"], rotation=90, fontsize=6, ha="center", va="bottom")
    ax.set_xticks(range(len(groups)), [f"{t.replace('_', ' ')}\n{size}" for size, t in groups], fontsize=7)
    ax.set(ylim=(0, 1), ylabel="share caught at the threshold",
           title="defects caught by size: each type's thirds, smallest first")
    fig.savefig(out / "by-size.png", dpi=120, bbox_inches="tight")
    plt.close(fig)
    return "by-size.png"
