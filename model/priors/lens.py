"""What a lens does to the light across the frame: its relative illumination (vignetting). Numpy only.

One place for the convention: the sensor model (``sim.sensor.lens``: a lens between the renders' pinhole camera and
the polarizers) and the look network's lens copies (``model.draem.lens_copies``: good parts as a lens would show
them) both read it.

Convention: ``cos^4`` of the field angle about the frame's centre (the optical axis), the angle at the frame's
corners chosen so they get ``1 - vignetting`` of the centre's irradiance; a factor on S0, S1 and S2 alike, so DoLP
and AoLP do not change. Frame pixels are indexed (row, column) with pixel centres at integers.
"""

from __future__ import annotations

import numpy as np


def _illumination(yy: np.ndarray, xx: np.ndarray, height: int, width: int, vignetting: float) -> np.ndarray:
    """The relative illumination at frame coordinates (``yy``, ``xx``) of a height x width frame (float32)."""
    if vignetting <= 0:
        return np.ones(np.broadcast(yy, xx).shape, np.float32)
    r = np.hypot(xx - (width - 1) / 2, yy - (height - 1) / 2) / np.hypot((width - 1) / 2, (height - 1) / 2)
    tan_corner = np.tan(np.arccos((1.0 - vignetting) ** 0.25))
    return (np.cos(np.arctan(r * tan_corner)) ** 4).astype(np.float32)


def relative_illumination(height: int, width: int, vignetting: float) -> np.ndarray:
    """(H, W) float32 share of the centre's irradiance each pixel of a height x width frame gets through the lens
    (all ones at ``vignetting`` 0)."""
    yy, xx = np.mgrid[0:height, 0:width].astype(np.float64)
    return _illumination(yy, xx, height, width, vignetting)


def view_illumination(frame: tuple[int, int], box: tuple[int, int, int, int], shape: tuple[int, int],
                      vignetting: float) -> np.ndarray:
    """(H, W) = ``shape`` float32 relative illumination over a view: the frame's (``frame`` (height, width) px) region
    ``box`` (top, left, height, width px) resized to ``shape``, read at each view pixel's centre (the field is
    smooth, so this is its area mean to well under 1e-3)."""
    top, left, bh, bw = box
    h, w = shape
    yy = top + (np.arange(h, dtype=np.float64) + 0.5) * bh / h - 0.5
    xx = left + (np.arange(w, dtype=np.float64) + 0.5) * bw / w - 0.5
    return _illumination(yy[:, None], xx[None, :], frame[0], frame[1], vignetting)
