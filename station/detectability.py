"""Detection by detectability: a detector's image-level results split by what the optics could show (the
detectability oracle's best-prior SNR, ``sim.oracle``), so each accuracy figure reads "of what the camera can see".

Rows per SNR bin (``sim.detectability.SNR_BINS``, by the best camera prior), for all defects and per defect type:
the defects in the bin, the share caught (image score > the threshold, as ``station eval``'s ``detected``) and the
image AUROC of those defects against every good part of the split.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from sim.detectability import SNR_BINS, best_snr, snr_bin

COLUMNS = ["type", "snr_bin", "defects", "caught", "image_auroc"]


def oracle_snr(records: Sequence[dict | None]) -> list[float | None]:
    """The best camera prior's SNR of each sample's defect record (``sim.dataset.defect_records``; None for good
    parts and sets without oracle values)."""
    return [best_snr(d) for d in records]


def detection_by_detectability(labels: Sequence[int], scores: Sequence[float], threshold: float | None,
                               snr: Sequence[float | None], types: Sequence[str]) -> list[dict]:
    """Rows (``COLUMNS``) for the defective samples that have an SNR; empty when none has. ``caught`` is NaN
    without a threshold, ``image_auroc`` NaN without good parts."""
    from model.draem.metrics import auroc

    y = np.asarray(labels, bool)
    s = np.asarray(scores, np.float64)
    has = np.array([v is not None for v in snr]) & y
    if not has.any():
        return []
    bins = np.array([snr_bin(v) if v is not None else "" for v in snr])
    kinds = np.asarray(types, dtype=object)
    rows = []
    for typ in ["all", *sorted({str(t) for t in kinds[has]})]:
        for _, _, name in SNR_BINS:
            sel = has & (bins == name) & ((kinds == typ) if typ != "all" else True)
            if not sel.any():
                continue
            caught = float(np.mean(s[sel] > threshold)) if threshold is not None else math.nan
            both = sel | ~y
            roc = auroc(y[both], s[both]) if (~y).any() else math.nan
            rows.append({"type": typ, "snr_bin": name, "defects": int(sel.sum()), "caught": caught,
                         "image_auroc": float(roc)})
    return rows
