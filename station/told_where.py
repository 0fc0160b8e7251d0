"""Detection against what the features show: ``station eval``'s rows and plot for the localised oracle
(``model.draem.localised_oracle``), so each type's miss reads as the optics' (the oracle told where does not separate
it either) or the detector's (the oracle does, the model does not).

Rows per defect type (all first): the defects with a mask, the share the oracle separates at ``FALSE_REJECT`` of good
parts by each statistic and by either, the share the model catches at its validation threshold for that same share
of good parts, the share it catches of those the oracle separates, and their image AUROC against the split's good
parts (issue 19's per-type target stated on the defects the optics show).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

FALSE_REJECT = 0.01
COLUMNS = ["type", "defects", "separable_pixels", "separable_mean", "separable", "caught", "caught_of_separable",
           "image_auroc_separable"]


def told_where(variation, priors, labels: np.ndarray, masks, mask_known: np.ndarray, types: list[str],
               scores: np.ndarray, threshold: float | None) -> tuple[list[dict], list[bool | None]]:
    """A model's variation model and a split's (N, C, H, W) priors, (N,) labels, (N, H, W) defect masks, (N,) whether
    each mask is known, (N,) defect types, (N,) decision scores and the threshold that rejects ``FALSE_REJECT`` of
    the validation set's good parts (None: ``caught`` is NaN) -> (rows (``COLUMNS``), per part whether the oracle
    separates it: None for good parts and defects without a mask); ([], all None) without good parts or defective
    parts with masks. ``image_auroc_separable``: the separable defects' scores against every good part's (NaN with
    none separable)."""
    from model.draem.localised_oracle import localised_oracle
    from model.draem.metrics import auroc

    labels = np.asarray(labels).astype(bool)
    keep = ~labels | (labels & np.asarray(mask_known, bool))
    per_part: list[bool | None] = [None] * len(labels)
    if labels[keep].all() or not labels[keep].any():
        return [], per_part
    idx = np.flatnonzero(keep)
    res = localised_oracle(variation, priors[idx], labels[idx].astype(int), masks[idx], FALSE_REJECT)
    bad = idx[labels[idx]]
    for k, i in enumerate(bad):
        per_part[i] = bool(res.separable[k])
    kinds = np.asarray(types, dtype=object)[bad]
    scores = np.asarray(scores, np.float64)
    caught = (scores[bad] > threshold) if threshold is not None else np.full(len(bad), np.nan)
    good, bad_scores = scores[~labels], scores[bad]
    rows = []
    for typ in ["all", *sorted({str(t) for t in kinds})]:
        sel = np.ones(len(bad), bool) if typ == "all" else kinds == typ
        sep = res.separable[sel]
        rows.append({"type": typ, "defects": int(sel.sum()),
                     "separable_pixels": float(res.separable_by[sel, 0].mean()),
                     "separable_mean": float(res.separable_by[sel, 1].mean()),
                     "separable": float(sep.mean()), "caught": float(np.mean(caught[sel])),
                     "caught_of_separable": float(np.mean(caught[sel][sep])) if sep.any() else math.nan,
                     "image_auroc_separable": auroc(np.r_[np.zeros(len(good)), np.ones(int(sep.sum()))],
                                                    np.r_[good, bad_scores[sel][sep]])})
    return rows, per_part


def plot(out: Path, rows: list[dict]) -> str:
    """Bars per type: separable by the oracle against caught by the model; returns the file name."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 3.2))
    x = np.arange(len(rows))
    ax.bar(x - 0.2, [r["separable"] for r in rows], 0.4, label="told where (localised oracle)")
    ax.bar(x + 0.2, [r["caught"] for r in rows], 0.4, label="the model, threshold from validation")
    ax.set_xticks(x, [r["type"].replace("_", " ") for r in rows], fontsize=8)
    ax.set(ylim=(0, 1), ylabel=f"share at {100 * FALSE_REJECT:g} % of good parts rejected",
           title="defects the features separate, and the defects caught")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2)
    fig.savefig(out / "told-where.png", dpi=120, bbox_inches="tight")
    plt.close(fig)
    return "told-where.png"
