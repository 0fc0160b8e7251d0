"""Lens copies: good training parts as a lens would show them, for the look network (``station residual
--lens-copies``).

The renders' camera is a pinhole; a real lens vignettes, a smooth fall of light toward the frame's corners
(``model.priors.lens``). The variation model's window is a curvature and does not see it, but the look network reads
the signed residual maps, where a few percent of fall across the part is a broad signed field no good training part
had: through a lens keeping 80 % of the light at the corners the shipped file rejected 7 of 146 good parts, the
window alone 2 (docs/results/2026-12-07-blend-otherwise.md). Fitting the whole recipe on lensed renders, or taking a
smooth field out of every frame, cost the line as built 4-6 points of defects caught (docs/results/2026-12-08-
lens-train.md, 2026-12-09-smooth-field.md); these copies change only what the network learns good parts look like.

A copy of each good part: its left-out signed z maps (what an unseen good part leaves, ``VariationModel.fit``) plus
what a lens drawn for it changes in them, ``zmaps(x * fall) - zmaps(x)`` through the fitted variation model (its
registration, appearance components, contrast alignment and noise level), where both frames are judged. The fall
is drawn per copy, uniform in the ``vignetting`` range (the share of light lost at the frame's corners), on the
intensity channel only (a lens's fall is a factor on S0, S1 and S2 alike: DoLP and AoLP do not change).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import torch

from model.priors.lens import view_illumination

from .errors import ModelError
from .variation import VariationModel


@dataclass(frozen=True)
class LensCopies:
    """How the look network's lens copies are drawn: ``vignetting`` (low, high), the share of light lost at the
    frame's corners, drawn uniformly per copy, within [0, 1); the frame (height, width px) and the model's view
    ``box`` (top, left, height, width px: ``model.draem.roi.roi_box``) in it, which place the view under the lens;
    ``seed`` of the draws."""

    vignetting: tuple[float, float]
    frame: tuple[int, int]
    box: tuple[int, int, int, int]
    seed: int = 0

    def __post_init__(self) -> None:
        lo, hi = self.vignetting
        if not (np.isfinite(lo) and np.isfinite(hi) and 0 <= lo <= hi < 1):
            raise ModelError(f"lens copies: vignetting must be a range 0 <= low <= high < 1, got {self.vignetting}")

    def to_record(self) -> dict:
        """A sidecar's record of the copies (JSON)."""
        return {"vignetting": list(self.vignetting), "frame": list(self.frame), "box": list(self.box),
                "seed": self.seed}


@torch.no_grad()
def lensed_signed(variation: VariationModel, good: torch.Tensor, signed: torch.Tensor, lens: LensCopies
                  ) -> torch.Tensor:
    """(N, C, H, W) signed z maps of the ``good`` parts' lens copies: their left-out ``signed`` maps (N, C, H, W)
    plus what a lens drawn per part changes in the fitted ``variation`` model's (``VariationModel``) signed maps of
    ``good`` (N, C, H, W priors), where both frames are judged (elsewhere the left-out maps as they are). Finite
    where ``signed`` is."""
    rng = np.random.default_rng(lens.seed)
    shape = tuple(good.shape[-2:])
    falls = np.stack([view_illumination(lens.frame, lens.box, shape, float(rng.uniform(*lens.vignetting)))
                      for _ in range(len(good))])
    lensed = good.clone()
    lensed[:, variation.intensity] *= torch.from_numpy(falls).to(lensed)
    base, seen = variation.zmaps(good, signed=True), variation.zmaps(lensed, signed=True)
    assert base.signed is not None and base.judged is not None and seen.signed is not None and seen.judged is not None
    both = (base.judged.bool() & seen.judged.bool())[:, None]
    change = torch.where(both, seen.signed - base.signed, torch.zeros_like(base.signed))
    return signed.float() + torch.nan_to_num(change.to(signed.device), nan=0.0, posinf=0.0, neginf=0.0)
