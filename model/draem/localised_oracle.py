"""What a variation model's features show of each defect: a localised oracle, the detector told where to look.

The station must find a defect anywhere on the part, so its threshold is set by the good parts' highest place
anywhere. The oracle knows each defect's pixels (its mask, registered as the model registers the frame, grown by
``GROW_PX``) and puts a statistic of the model's residual there against every good part of the same set at the same
pixels. A defect above ``1 - false_reject`` of those good parts is one a detector told where to look could catch at
that share of good parts rejected: what the camera's priors, after the line's own variation, show of it. It bounds
what any detector on these features can catch, and says which misses are the detector's and which the optics'
(docs/results/2026-11-25-physical-anomalies.md, section 4, and 2026-11-27-panel-oracle.md, where it was a study).

Two statistics, of the signed residual z over the channels (``VariationModel.zmaps(signed=True)``: in units of the
good parts' spread, after the frame's noise level, judged pixels only):
- "pixels": the mean over the mask's judged pixels of the chi-square over the channels (a change anywhere);
- "mean": the chi-square over the channels of the residual averaged over those pixels first (a change of one sign
  across the defect, pixel noise averaged out).
A defect is separable when either statistic is (so up to twice ``false_reject`` of good parts would be above one of
them). numpy, OpenCV and torch; a defect whose mask registers outside the judged part is not separable.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np
import torch

from model.draem.variation import VariationModel

GROW_PX = 1
"""A defect's registered mask is grown by this many pixels (its edge mixes defect and part)."""

BATCH = 50
"""Frames scored at a time: only each frame's statistics over the masks are kept, not its residual maps."""


@dataclass(frozen=True)
class OracleResult:
    """Per defective part (in the order given): its two statistics at its own pixels, the good parts' ``1 -
    false_reject`` quantile of each there, and whether either lies above."""

    defect: np.ndarray  # (D, 2) float64: "pixels", "mean"
    limit: np.ndarray  # (D, 2) float64
    false_reject: float

    @property
    def separable_by(self) -> np.ndarray:
        """(D, 2) bool: above the good parts' quantile, per statistic."""
        return self.defect > self.limit

    @property
    def separable(self) -> np.ndarray:
        """(D,) bool: above it by either statistic."""
        return self.separable_by.any(1)


def _all_statistics(vm: VariationModel, x: torch.Tensor, masks: np.ndarray) -> np.ndarray:
    """(N, C, H, W) priors and (M, H*W) masks -> (N, M, 2) ``statistics`` of every frame over every mask."""
    out = []
    for i in range(0, len(x), BATCH):
        o = vm.zmaps(x[i:i + BATCH], signed=True)
        n = len(o.signed)
        out.append(statistics(o.signed.numpy().reshape(n, o.signed.shape[1], -1),
                              o.judged.numpy().reshape(n, -1).astype(np.float32), masks))
    return np.concatenate(out)


def statistics(z: np.ndarray, judged: np.ndarray, masks: np.ndarray) -> np.ndarray:
    """(N, C, P) signed z, (N, P) judged (0/1) and (M, P) masks (0/1) -> (N, M, 2) the two statistics (module
    docstring) of every part over every mask's judged pixels; 0 where a mask holds none of a part's judged pixels."""
    m = masks.astype(np.float32).T  # (P, M)
    count = judged @ m  # (N, M)
    safe = np.maximum(count, 1.0)
    pixels = ((z**2).sum(1) * judged) @ m / safe
    mean = sum(((z[:, c] * judged) @ m / safe) ** 2 for c in range(z.shape[1]))
    out = np.stack([pixels, mean], axis=-1).astype(np.float64)
    return np.where((count > 0)[..., None], out, 0.0)


def localised_oracle(vm: VariationModel, priors: torch.Tensor, labels: np.ndarray, masks: torch.Tensor,
                     false_reject: float = 0.01) -> OracleResult:
    """A fitted variation model, a set's (N, C, H, W) priors at its input, (N,) labels (1 = defective) and (N, H, W)
    defect masks at the same size -> the oracle (module docstring) for each defective part, in order. The good
    parts of the same set are the reference: at least ``1 / false_reject`` of them make the quantile mean what it
    says. ValueError without good or defective parts."""
    labels = np.asarray(labels).astype(bool)
    if labels.all() or not labels.any():
        raise ValueError("the localised oracle needs good and defective parts in the same set")
    if not 0.0 < false_reject < 1.0:
        raise ValueError(f"false_reject {false_reject}: a fraction in (0, 1)")
    x = priors.float()
    bad = np.flatnonzero(labels)
    registered = vm.register_masks(x[bad], masks[bad].bool()).numpy()
    grow = np.ones((2 * GROW_PX + 1,) * 2, np.uint8)
    grown = np.stack([cv2.dilate(m.astype(np.uint8), grow) for m in registered]).reshape(len(bad), -1)
    stats = _all_statistics(vm, x, grown)  # (N, D, 2)
    own = stats[bad, np.arange(len(bad))]  # (D, 2): each defect at its own pixels
    limit = np.percentile(stats[~labels], 100.0 * (1.0 - false_reject), axis=0)  # the good parts there
    return OracleResult(own, limit, false_reject)
