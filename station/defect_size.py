"""Detection by defect size: a detector's image-level results per defect type, split into thirds by the physical
size that governs each type's visibility (``sim.defects.defect_size``: a dent's steepest tilt, a scratch's area, a
stain's radius, a chip's cut), so a line can state which defects of a type it catches, not only how many.

Rows per type with sizes (missing studs are all alike): each third of that type's defects in the split, by size
(equal counts; the last third takes the remainder), with the size range, the defects, the share caught (image score
> the threshold, as ``station eval``'s ``detected``) and the image AUROC of those defects against every good part.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from sim.dataset import defect_records
from sim.defects import defect_size

COLUMNS = ["type", "size", "range", "defects", "caught", "image_auroc"]
PARTS = 3
"""Size bins per type: thirds (with about 45 defects of a type in a 400-part set, 15 a bin)."""


def defect_sizes(root: str | Path, indices: Sequence[int]) -> list[tuple[str, float] | None]:
    """Each sample's ``defect_size`` (None for good parts and defects without one), from its ``params.json``."""
    return [defect_size(d) for d in defect_records(root, indices)]


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
            rows.append({"type": typ, "size": known[int(part[0])][0], "range": f"{min(vals):.3g}-{max(vals):.3g}",
                         "defects": int(sel.sum()), "caught": caught, "image_auroc": float(roc)})
    return rows


def plot(out: Path, rows: list[dict]) -> str:
    """Bars per type, one per third by size (smallest first), of the share caught; returns the file name."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    types = list(dict.fromkeys(r["type"] for r in rows))
    fig, ax = plt.subplots(figsize=(6.5, 3.2))
    width = 0.8 / PARTS
    for k, typ in enumerate(types):
        mine = [r for r in rows if r["type"] == typ]
        for j, r in enumerate(mine):
            x = k - 0.4 + width * (j + 0.5)
            ax.bar(x, r["caught"], width * 0.9, color=f"C{j}")
            ax.text(x, 0.01, r["range"], rotation=90, fontsize=6, ha="center", va="bottom")
    ax.set_xticks(range(len(types)), [f"{t.replace('_', ' ')}\n({next(r['size'] for r in rows if r['type'] == t)})"
                                      for t in types], fontsize=8)
    ax.set(ylim=(0, 1), ylabel="share caught at the threshold",
           title="defects caught by size: each type's thirds, smallest first")
    fig.savefig(out / "by-size.png", dpi=120, bbox_inches="tight")
    plt.close(fig)
    return "by-size.png"
