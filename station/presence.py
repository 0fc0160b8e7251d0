"""Is a part in view? A cheap check on the prior maps the inspector already computed, run before the model.

Two rules, one per kind of view (``[presence] rule`` in ``station.toml``); both average the map over cells of
``cell_px`` x ``cell_px`` pixels inside the square the model scores (``model.draem.roi.center_box``), fit a smooth
background to the cell means by least squares, and take the largest absolute residual as the contrast. A part is
present when the contrast is at least the rule's threshold. Cell means average out Monte-Carlo and sensor noise and
the demosaic's false DoLP at checkerboard edges; the smooth fit takes out the background's gradients.

``dolp_contrast`` (default; a camera looking down at the belt): the DoLP map less a quadratic surface in (x, y);
DoLP units. An empty view is one background plane under one light, whose polarization varies smoothly over the
few centimetres the camera sees (glossy grounds near Brewster's angle reach DoLP 0.65 everywhere, so a plain DoLP
level does not work); a part adds a bump of faces polarized differently from the ground, and shadows. Measured on
rendered 640x480 frames (docs/station.md): 184 parts have contrast >= 0.140 with every demosaic method; of 124
empty views 123 have <= 0.087 and one 0.138 (a polarizing checkerboard whose squares are larger than the view: a
real DoLP step the quadratic cannot follow).

``row_contrast`` (a camera looking level at the part across the belt, as ``sim/presets/side-view.toml``): each row
of intensity cells less its own quadratic in x, over the median cell; a share of the view's level, so the same
under any exposure. Seen level, an empty view is a backdrop over the belt: bands that change from row to row (the
belt's edge is a sharp step) but little along a row; a part is a block of columns that differ from their row.
Looked at square-on, a front face's DoLP is low, like the backdrop's, so ``dolp_contrast`` does not see it: on the
side camera's 600 validation frames of the wide-dome line (``data/sw-pv-val``, all with a part) it called 78
empty, and on 80 empty views of the same scenes it reached 0.35 (the belt's edge). There ``row_contrast`` is
>= 0.22 on every part and <= 0.04 on every empty view (docs/station.md).

Both defaults (0.10) err toward "present": a missed empty view is judged by the model as before this check
existed, while a missed part is never judged (trigger-free) or rejected unseen (triggered).
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass
from enum import StrEnum
from typing import TYPE_CHECKING, Self

import cv2
import numpy as np

from model.draem.roi import center_box

if TYPE_CHECKING:
    from station.config import PresenceConfig

MIN_CELLS = 8
"""At least 8 x 8 cells whatever the frame size: on fewer, the quadratic (6 coefficients) absorbs a part too."""


class PresenceRule(StrEnum):
    """Which contrast decides "part in view" (see the module docstring); the value is the config's name."""

    DOLP_CONTRAST = "dolp_contrast"
    ROW_CONTRAST = "row_contrast"

    @property
    def prior(self) -> str:
        """The prior map the rule reads."""
        return "dolp" if self is PresenceRule.DOLP_CONTRAST else "intensity"

    @property
    def measure(self) -> str:
        """The contrast's name and unit, for reasons."""
        return "DoLP contrast" if self is PresenceRule.DOLP_CONTRAST else "row contrast (share of level)"


@dataclass(frozen=True)
class Presence:
    """The check's answer for one frame: ``contrast`` (the rule's units) compared with ``threshold``."""

    present: bool
    contrast: float
    threshold: float
    rule: PresenceRule = PresenceRule.DOLP_CONTRAST

    @property
    def reason(self) -> str:
        """Why a frame was judged empty (for the log and the PLC)."""
        return f"no part in view: {self.rule.measure} {self.contrast:.3f} < {self.threshold:.3f}"


@functools.lru_cache(maxsize=8)
def _quadratic_basis(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Design matrix (n*n, 6) of a quadratic in (x, y) over an n x n grid (x, y in [-0.5, 0.5]) and its
    pseudo-inverse (6, n*n): ``a @ (pinv @ v)`` is the least-squares fit of ``v``."""
    y, x = (np.mgrid[0:n, 0:n] / (n - 1) - 0.5).reshape(2, -1)
    a = np.stack([np.ones_like(x), x, y, x * x, y * y, x * y], axis=1)
    return a.astype(np.float32), np.linalg.pinv(a).astype(np.float32)


@functools.lru_cache(maxsize=8)
def _row_basis(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Design matrix (n, 3) of a quadratic in x over n cells (x in [-0.5, 0.5]) and its pseudo-inverse (3, n)."""
    x = np.linspace(-0.5, 0.5, n)
    a = np.stack([np.ones_like(x), x, x * x], axis=1)
    return a.astype(np.float32), np.linalg.pinv(a).astype(np.float32)


def cell_means(image: np.ndarray, cell_px: int) -> np.ndarray:
    """(n, n) means of ``cell_px``-pixel cells of a (H, W) map inside its centre square, the square trimmed to whole
    cells (centred), at least ``MIN_CELLS`` per side."""
    if image.ndim != 2:
        raise ValueError(f"prior map must be (H, W), got shape {image.shape}")
    top, left, side, _ = center_box(*image.shape)
    if side < MIN_CELLS:
        raise ValueError(f"prior map {image.shape} too small for the presence check ({MIN_CELLS} cells per side)")
    n = max(side // cell_px, MIN_CELLS)
    cell = side // n
    top, left = top + (side - n * cell) // 2, left + (side - n * cell) // 2
    roi = image[top:top + n * cell, left:left + n * cell].astype(np.float32, copy=False)
    # an integer shrink factor makes INTER_AREA an exact box mean, and 6x faster than a fractional one
    return cv2.resize(roi, (n, n), interpolation=cv2.INTER_AREA)


def dolp_contrast(dolp: np.ndarray, cell_px: int = 12) -> float:
    """Largest |cell mean - smooth background| of a (H, W) DoLP map inside its centre square (see module), in DoLP
    units (0..1)."""
    cells = cell_means(dolp, cell_px)
    a, pinv = _quadratic_basis(cells.shape[0])
    v = cells.reshape(-1)
    return float(np.abs(v - a @ (pinv @ v)).max())


def row_contrast(intensity: np.ndarray, cell_px: int = 12) -> float:
    """Largest |cell mean - its row's quadratic in x| of a (H, W) intensity map inside its centre square (see
    module), over the median cell mean: a share of the view's level (any intensity unit). 0 for a black view."""
    cells = cell_means(intensity, cell_px)
    a, pinv = _row_basis(cells.shape[1])
    residual = cells - (a @ (pinv @ cells.T)).T
    level = float(np.median(cells))
    return float(np.abs(residual).max() / level) if level > 0 else 0.0


class PresenceCheck:
    """Callable on a frame's prior maps; rule and thresholds from ``[presence]`` in ``station.toml``."""

    def __init__(self, min_dolp_contrast: float = 0.10, cell_px: int = 12,
                 rule: PresenceRule | str = PresenceRule.DOLP_CONTRAST, min_row_contrast: float = 0.10) -> None:
        if not 0.0 <= min_dolp_contrast <= 1.0:
            raise ValueError(f"min_dolp_contrast must be in [0, 1], got {min_dolp_contrast}")
        if not 0.0 <= min_row_contrast <= 10.0:
            raise ValueError(f"min_row_contrast must be in [0, 10], got {min_row_contrast}")
        if cell_px < 1:
            raise ValueError(f"cell_px must be >= 1, got {cell_px}")
        self.rule = PresenceRule(rule)
        self.min_dolp_contrast = min_dolp_contrast
        self.min_row_contrast = min_row_contrast
        self.cell_px = cell_px
        self.priors = (self.rule.prior,)
        """Prior maps the check reads (the inspector computes them even when the model does not need them)."""

    @classmethod
    def from_config(cls, p: PresenceConfig, rule: PresenceRule | str | None = None) -> Self:
        """The check ``[presence]`` sets (``rule``: another than ``[presence] rule``, as the second camera's)."""
        return cls(p.min_dolp_contrast, p.cell_px, rule or p.rule, p.min_row_contrast)

    @property
    def threshold(self) -> float:
        """The rule's threshold (its contrast's units)."""
        return self.min_dolp_contrast if self.rule is PresenceRule.DOLP_CONTRAST else self.min_row_contrast

    def __call__(self, priors: Mapping[str, np.ndarray]) -> Presence:
        measure = dolp_contrast if self.rule is PresenceRule.DOLP_CONTRAST else row_contrast
        contrast = measure(priors[self.rule.prior], self.cell_px)
        return Presence(contrast >= self.threshold, contrast, self.threshold, self.rule)
