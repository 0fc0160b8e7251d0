"""Raw polarizer mosaics: normalisation to full scale with input checks, and Stokes -> mosaic sampling.

Conventions (layout, angles, units): ``conventions.py``.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from .conventions import MosaicLayout, full_scale, get_layout
from .stokes import stokes_to_intensity


@dataclass(frozen=True)
class NormalizedMosaic:
    """A mosaic in full-scale float32 units plus what was wrong with the input (nothing is silently fixed).

    ``invalid`` marks pixels that were NaN/Inf (set to 0) or out of range (clipped); None when there were none.
    """

    data: np.ndarray
    n_nonfinite: int
    n_out_of_range: int
    n_saturated: int
    invalid: np.ndarray | None


def check_mosaic(raw: np.ndarray) -> None:
    """Raise ValueError naming the shape or dtype unless ``raw`` is a 2-D mosaic with even sides."""
    if not isinstance(raw, np.ndarray):
        raise TypeError(f"raw mosaic must be a numpy array, got {type(raw).__name__}")
    if raw.ndim != 2:
        raise ValueError(f"raw mosaic must be 2-D (height, width), got shape {raw.shape}")
    h, w = raw.shape
    if h < 2 or w < 2 or h % 2 or w % 2:
        raise ValueError(f"raw mosaic sides must be even and >= 2 (whole 2x2 superpixels), got shape {raw.shape}")
    if not (raw.dtype in (np.uint8, np.uint16) or np.issubdtype(raw.dtype, np.floating)):
        raise TypeError(f"raw mosaic dtype must be uint8, uint16 or float, got {raw.dtype}")


def normalize_mosaic(raw: np.ndarray, bit_depth: int | None = None) -> NormalizedMosaic:
    """Convert a raw mosaic to float32 full-scale units (1.0 = largest code of ``bit_depth``).

    uint8/uint16 inputs: codes above ``2**bit_depth - 1`` (junk in the unused bits) are clipped and counted.
    Float inputs are taken as full-scale units already; NaN/Inf become 0 and values outside [0, 1] (no sensor
    gives a negative or over-full-scale reading) are clipped to it, both counted and marked in ``invalid``.
    """
    check_mosaic(raw)
    fs = full_scale(raw.dtype, bit_depth)
    if np.issubdtype(raw.dtype, np.floating):
        data = np.array(raw, dtype=np.float32)  # always a copy: the caller's frame is not ours to change
        nonfinite = ~np.isfinite(data)
        n_nonfinite = int(np.count_nonzero(nonfinite))
        if n_nonfinite:
            data[nonfinite] = 0.0
        out_of_range = (data < 0.0) | (data > 1.0)
        n_out = int(np.count_nonzero(out_of_range))
        if n_out:
            np.clip(data, 0.0, 1.0, out=data)
        n_saturated = int(np.count_nonzero(data >= 1.0))
        invalid = (nonfinite | out_of_range) if (n_nonfinite or n_out) else None
        return NormalizedMosaic(data, n_nonfinite, n_out, n_saturated, invalid)

    n_out, invalid = 0, None
    if fs < np.iinfo(raw.dtype).max:
        over = raw > fs
        n_out = int(np.count_nonzero(over))
        if n_out:
            invalid = over
            raw = np.minimum(raw, raw.dtype.type(fs))
    n_saturated = int(np.count_nonzero(raw >= fs))
    data = cv2.multiply(raw, 1.0 / fs, dtype=cv2.CV_32F)
    return NormalizedMosaic(data, 0, n_out, n_saturated, invalid)


def stokes_to_mosaic(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray,
                     layout: str | MosaicLayout = "imx250mzr") -> np.ndarray:
    """Sample Stokes images (H, W) through the on-chip polarizers: the ideal float32 mosaic a DoFP sensor
    sees, ``I(t) = 0.5 * (S0 + S1 cos 2t + S2 sin 2t)`` with ``t`` from ``layout`` at each pixel."""
    lay = get_layout(layout)
    angles = np.deg2rad(lay.angle_map(*np.shape(s0)).astype(np.float32))
    return stokes_to_intensity(s0, angles, s1, s2)


def split_superpixels(mosaic: np.ndarray, layout: str | MosaicLayout = "imx250mzr") -> np.ndarray:
    """The four polarizer images at half resolution (4, H/2, W/2), ordered 0, 45, 90, 135 degrees."""
    lay = get_layout(layout)
    return np.stack([mosaic[r::2, c::2] for r, c in (lay.position(a) for a in (0, 45, 90, 135))])
