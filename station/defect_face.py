"""Detection by face: a detector's image-level results per face of the part the defects lie on
(``sim.defects.defect_face``: top, front, back, end, bottom, edge), per type and over all types, so a report says
which faces the camera's optics serve. On the shipped line the top face mirrors the bright-field panel and the front
face mirrors the belt, which no light above the belt fills (docs/second-camera.md).

Rows: per face, all types together, then each type on it: the defects, the share caught (image score > the
threshold, as ``station eval``'s ``detected``) and the image AUROC of those defects against every good part.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from sim.defects import FACES

COLUMNS = ["face", "type", "defects", "caught", "image_auroc"]


def by_face(faces: Sequence[str | None], labels: Sequence[int], scores: Sequence[float],
            threshold: float | None, types: Sequence[str]) -> list[dict]:
    """Rows (``COLUMNS``) per face in ``FACES`` order ("all" types first), from each sample's face
    (``sim.defects.defect_face`` of its defect record; None when unknown, ignored for good parts); empty when no
    defect has a face. ``caught`` is NaN without a threshold, ``image_auroc`` NaN without good parts."""
    from model.draem.metrics import auroc

    y = np.asarray(labels, bool)
    s = np.asarray(scores, np.float64)
    face = [f if y[i] else None for i, f in enumerate(faces)]
    rows = []
    for f in FACES:
        on = [i for i, g in enumerate(face) if g == f]
        for typ in ["all", *sorted({str(types[i]) for i in on})]:
            sel = np.zeros(len(y), bool)
            sel[[i for i in on if typ == "all" or types[i] == typ]] = True
            if not sel.any():
                continue
            both = sel | ~y
            rows.append({"face": f, "type": typ, "defects": int(sel.sum()),
                         "caught": float(np.mean(s[sel] > threshold)) if threshold is not None else math.nan,
                         "image_auroc": float(auroc(y[both], s[both])) if (~y).any() else math.nan})
    return rows


def plot(out: Path, rows: list[dict]) -> str:
    """Bars of the share caught per face, all types together; returns the file name."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    mine = [r for r in rows if r["type"] == "all"]
    fig, ax = plt.subplots(figsize=(1.0 + 0.8 * len(mine), 3.0))
    ax.bar(range(len(mine)), [r["caught"] for r in mine], 0.7)
    ax.set_xticks(range(len(mine)), [f"{r['face']}\n{r['defects']} defects" for r in mine], fontsize=7)
    ax.set(ylim=(0, 1), ylabel="share caught at the threshold", title="defects caught by the face they lie on")
    fig.savefig(out / "by-face.png", dpi=120, bbox_inches="tight")
    plt.close(fig)
    return "by-face.png"
