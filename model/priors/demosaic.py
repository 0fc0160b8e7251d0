"""Polarization demosaicking: full-scale float32 mosaic -> four polarizer images or Stokes parameters.

Methods are registered by name in ``METHODS``:

bilinear    Each polarizer channel interpolated from its 2 or 4 nearest samples (the common baseline, as
            polanalyser's). Computed straight to Stokes: S1, S2 are linear in the channels, so each is one 3x3
            filter over the mosaic modulated by +1/-1 at the 0/90 (45/135) sites.
superpixel  Each 2x2 superpixel gives one output pixel (half resolution, no interpolation): fastest.

Conventions (layout, order 0/45/90/135, units): ``conventions.py``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

import cv2
import numpy as np

from .conventions import POLARIZER_ANGLES_DEG, MosaicLayout, get_layout
from .mosaic import split_superpixels
from .residual import residual_intensities, residual_stokes
from .stokes import intensities_to_stokes

Stokes = tuple[np.ndarray, np.ndarray | None, np.ndarray | None]

# Bilinear interpolation of a channel sampled on every other row and column, as a 3x3 filter of the
# zero-filled channel; its taps sum to 4 because a quarter of the pixels are samples.
BILINEAR_KERNEL = np.array([[1, 2, 1], [2, 4, 2], [1, 2, 1]], dtype=np.float32) / 4
# REFLECT_101 mirrors about the edge pixel, so a mirrored pixel keeps its polarizer angle (same parity).
BORDER = cv2.BORDER_REFLECT_101


@dataclass(frozen=True)
class DemosaicMethod:
    """A demosaicking method. ``intensities`` returns (4, H', W') images at 0/45/90/135 degrees; ``stokes``,
    when given, is a faster direct path returning (S0, S1, S2) with S1, S2 None unless ``polarization``."""

    name: str
    intensities: Callable[[np.ndarray, MosaicLayout], np.ndarray]
    stokes: Callable[[np.ndarray, MosaicLayout, bool], Stokes] | None = None
    half_resolution: bool = False


def filter3x3(image: np.ndarray, kernel: np.ndarray) -> np.ndarray:
    """3x3 correlation with the border mirrored so the mosaic phase is kept (``BORDER``)."""
    return cv2.filter2D(image, cv2.CV_32F, kernel, borderType=BORDER)


@lru_cache(maxsize=8)
def _modulation(layout: MosaicLayout, height: int, width: int) -> tuple[np.ndarray, np.ndarray]:
    """(+1 at 0, -1 at 90 degrees, else 0) and (+1 at 45, -1 at 135 degrees, else 0), float32 (H, W)."""
    angles = layout.angle_map(height, width)
    m1 = ((angles == 0).astype(np.float32) - (angles == 90)).astype(np.float32)
    m2 = ((angles == 45).astype(np.float32) - (angles == 135)).astype(np.float32)
    m1.flags.writeable = False
    m2.flags.writeable = False
    return m1, m2


def bilinear_intensities(mosaic: np.ndarray, layout: MosaicLayout) -> np.ndarray:
    """Four bilinearly interpolated polarizer images (4, H, W)."""
    angles = layout.angle_map(*mosaic.shape)
    return np.stack([filter3x3(np.where(angles == a, mosaic, np.float32(0)), BILINEAR_KERNEL)
                     for a in POLARIZER_ANGLES_DEG])


def bilinear_stokes(mosaic: np.ndarray, layout: MosaicLayout, polarization: bool) -> Stokes:
    """(S0, S1, S2) of the bilinear demosaic in three filters (one when only S0 is needed)."""
    s0 = filter3x3(mosaic, BILINEAR_KERNEL * np.float32(0.5))
    if not polarization:
        return s0, None, None
    m1, m2 = _modulation(layout, *mosaic.shape)
    s1 = filter3x3(cv2.multiply(mosaic, m1), BILINEAR_KERNEL)
    s2 = filter3x3(cv2.multiply(mosaic, m2), BILINEAR_KERNEL)
    return s0, s1, s2


def superpixel_intensities(mosaic: np.ndarray, layout: MosaicLayout) -> np.ndarray:
    """The four polarizer images at half resolution (4, H/2, W/2), no interpolation."""
    return np.ascontiguousarray(split_superpixels(mosaic, layout), dtype=np.float32)


METHODS: dict[str, DemosaicMethod] = {
    "bilinear": DemosaicMethod("bilinear", bilinear_intensities, bilinear_stokes),
    "superpixel": DemosaicMethod("superpixel", superpixel_intensities, half_resolution=True),
    "residual": DemosaicMethod("residual", residual_intensities, residual_stokes),
}


def get_method(method: str) -> DemosaicMethod:
    try:
        return METHODS[method]
    except KeyError:
        raise ValueError(f"unknown demosaic method {method!r}; known: {', '.join(METHODS)}") from None


def demosaic(mosaic: np.ndarray, layout: str | MosaicLayout = "imx250mzr", method: str = "bilinear"
             ) -> np.ndarray:
    """Four polarizer images (4, H', W') at 0, 45, 90, 135 degrees from a full-scale float32 mosaic."""
    return get_method(method).intensities(mosaic, get_layout(layout))


def mosaic_to_stokes(mosaic: np.ndarray, layout: str | MosaicLayout = "imx250mzr",
                     method: str = "bilinear", polarization: bool = True) -> Stokes:
    """(S0, S1, S2) float32 from a full-scale float32 mosaic; S1, S2 are None unless ``polarization``."""
    m = get_method(method)
    lay = get_layout(layout)
    if m.stokes is not None:
        return m.stokes(mosaic, lay, polarization)
    s0, s1, s2 = intensities_to_stokes(m.intensities(mosaic, lay))
    return (s0, s1, s2) if polarization else (s0, None, None)
