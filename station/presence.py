"""Is a part in view? A cheap check on the DoLP map the inspector already computed, run before the model.

Rule (``dolp_contrast``): inside the square the model scores (``model.draem.roi.center_box``), the DoLP
map is averaged over cells of ``cell_px`` x ``cell_px`` pixels, a quadratic surface in (x, y) is fitted to the
cell means by least squares, and the contrast is the largest absolute residual. A part is present when the
contrast is at least the threshold.

Why this rule: an empty view is one background plane under one light, whose polarization varies smoothly over
the few centimetres the camera sees (glossy grounds near Brewster's angle reach DoLP 0.65 everywhere, so a plain
DoLP level does not work); a part adds a bump of faces polarized differently from the ground, and shadows.
Cell means average out Monte-Carlo and sensor noise and the demosaic's false DoLP at checkerboard edges; the
quadratic takes out the ground's gradients. Measured on rendered 640x480 frames (docs/station.md): 184 parts have
contrast >= 0.140 with every demosaic method; of 124 empty views 123 have <= 0.087 and one 0.138 (a polarizing
checkerboard whose squares are larger than the view: a real DoLP step the quadratic cannot follow). The default
threshold 0.10 errs toward "present": a missed empty view is judged by the model as before this check existed,
while a missed part is never judged (trigger-free) or rejected unseen (triggered).

DoLP is in [0, 1] (``model.priors.conventions``); the contrast is in DoLP units.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass

import cv2
import numpy as np

from model.draem.roi import center_box

MIN_CELLS = 8
"""At least 8 x 8 cells whatever the frame size: on fewer, the quadratic (6 coefficients) absorbs a part too."""


@dataclass(frozen=True)
class Presence:
    """The check's answer for one frame: ``contrast`` in DoLP units, compared with ``threshold``."""

    present: bool
    contrast: float
    threshold: float

    @property
    def reason(self) -> str:
        """Why a frame was judged empty (for the log and the PLC)."""
        return f"no part in view: DoLP contrast {self.contrast:.3f} < {self.threshold:.3f}"


@functools.lru_cache(maxsize=8)
def _quadratic_basis(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Design matrix (n*n, 6) of a quadratic in (x, y) over an n x n grid (x, y in [-0.5, 0.5]) and its
    pseudo-inverse (6, n*n): ``a @ (pinv @ v)`` is the least-squares fit of ``v``."""
    y, x = (np.mgrid[0:n, 0:n] / (n - 1) - 0.5).reshape(2, -1)
    a = np.stack([np.ones_like(x), x, y, x * x, y * y, x * y], axis=1)
    return a.astype(np.float32), np.linalg.pinv(a).astype(np.float32)


def dolp_contrast(dolp: np.ndarray, cell_px: int = 12) -> float:
    """Largest |cell mean - smooth background| of a (H, W) DoLP map inside its centre square (see module).
    The square is trimmed to whole cells (centred), at least ``MIN_CELLS`` per side."""
    if dolp.ndim != 2:
        raise ValueError(f"DoLP map must be (H, W), got shape {dolp.shape}")
    top, left, side, _ = center_box(*dolp.shape)
    if side < MIN_CELLS:
        raise ValueError(f"DoLP map {dolp.shape} too small for the presence check ({MIN_CELLS} cells per side)")
    n = max(side // cell_px, MIN_CELLS)
    cell = side // n
    top, left = top + (side - n * cell) // 2, left + (side - n * cell) // 2
    roi = dolp[top:top + n * cell, left:left + n * cell].astype(np.float32, copy=False)
    # an integer shrink factor makes INTER_AREA an exact box mean, and 6x faster than a fractional one
    cells = cv2.resize(roi, (n, n), interpolation=cv2.INTER_AREA).reshape(-1)
    a, pinv = _quadratic_basis(n)
    residual = cells - a @ (pinv @ cells)
    return float(np.abs(residual).max())


class PresenceCheck:
    """Callable on a frame's prior maps (needs "dolp"); thresholds from ``[presence]`` in ``station.toml``."""

    priors = ("dolp",)
    """Prior maps the check reads (the inspector computes them even when the model does not need them)."""

    def __init__(self, min_dolp_contrast: float = 0.10, cell_px: int = 12) -> None:
        if not 0.0 <= min_dolp_contrast <= 1.0:
            raise ValueError(f"min_dolp_contrast must be in [0, 1], got {min_dolp_contrast}")
        if cell_px < 1:
            raise ValueError(f"cell_px must be >= 1, got {cell_px}")
        self.min_dolp_contrast = min_dolp_contrast
        self.cell_px = cell_px

    def __call__(self, priors: Mapping[str, np.ndarray]) -> Presence:
        contrast = dolp_contrast(priors["dolp"], self.cell_px)
        return Presence(contrast >= self.min_dolp_contrast, contrast, self.min_dolp_contrast)
