"""A camera's black level: the code its pixels read with no light, removed before the demosaic.

Cameras add a pedestal (``BlackLevel`` in GenICam) to every code, so that read noise below black is not clipped.
The Stokes images are linear in light from zero: a pedestal ``b`` read as light adds ``2 b`` to S0 and nothing to
S1, S2, so it lowers DoLP everywhere, most on the darkest pixels. The renders the models learn from have none
(``sim.sensor.SensorConfig.black_level_dn = 0``).

Convention: a code ``c`` of a frame whose largest code is ``M = 2**bit_depth - 1`` becomes
``round((c - b) * M / (M - b))``, at least 0, in the frame's own dtype. So 0 is no light and ``M`` is still the
brightest reading the sensor can give: a pixel clipped at the ADC's top stays at full scale, where the
priors count it saturated and the model's highlight rule (``model.draem.variation.HIGHLIGHT_LEVEL``) looks for it.
Codes below ``b`` (read noise in the dark) become 0, as the renders' sensor model clips them.

The black level is measured with the lens capped, from the same frames ``station defect-pixels`` reads: the
median code of every pixel of the frames whose median is dark (``measure_black_level``).
"""

from __future__ import annotations

from collections.abc import Sequence

import cv2
import numpy as np

from .conventions import full_scale
from .mosaic import check_mosaic


def check_black_level(black_level: int, bit_depth: int) -> None:
    """ValueError unless ``black_level`` is a code below full scale of ``bit_depth`` bits."""
    top = 2**bit_depth - 1
    if isinstance(black_level, bool) or not isinstance(black_level, int | np.integer) or not 0 <= black_level < top:
        raise ValueError(f"black level {black_level!r} must be a whole code in [0, {top}) for {bit_depth}-bit codes")


def subtract_black_level(raw: np.ndarray, black_level: int, bit_depth: int | None = None) -> np.ndarray:
    """``raw`` (uint8/uint16 codes of ``bit_depth`` significant bits; default the dtype's) with ``black_level``
    removed and full scale kept (module docstring); ``raw`` itself when ``black_level`` is 0. Codes above full scale
    (junk in unused bits) stay above it, so the priors still count them out of range. ValueError when the
    black level is not below full scale, or the frame is not integer codes."""
    if black_level == 0:
        return raw
    check_mosaic(raw)
    if not np.issubdtype(raw.dtype, np.integer):
        raise ValueError(f"a black level applies to integer codes, not a {raw.dtype} frame")
    top = full_scale(raw.dtype, bit_depth)
    check_black_level(black_level, int(np.log2(top + 1)))
    above = cv2.subtract(raw, np.full_like(raw, black_level))  # saturates at 0
    # rounds, in raw's dtype: codes up to full scale stay within it; junk above it (bits beyond ``bit_depth``) stays
    # above, where ``normalize_mosaic`` counts it out of range
    return cv2.multiply(above, np.ones_like(raw), scale=top / (top - black_level))


DARK_SHARE = 0.05
"""A frame whose median code is below this share of full scale counts as taken with the lens capped
(``measure_black_level``): pedestals are a few percent of full scale at most, an evenly lit target is far above."""


def measure_black_level(frames: Sequence[np.ndarray], bit_depth: int | None = None) -> tuple[int, int] | None:
    """(black level, frames read) from the frames taken with the lens capped among ``frames`` (uint8/uint16 codes of
    ``bit_depth`` bits): the median code over every pixel of every frame whose own median is below ``DARK_SHARE`` of
    full scale (hot and dead pixels are a few in a million and do not move it). None when no frame is dark.
    ValueError for frames of mixed sizes or dtypes."""
    if not frames:
        return None
    first = frames[0]
    for f in frames:
        check_mosaic(f)
        if f.shape != first.shape or f.dtype != first.dtype:
            raise ValueError(f"frames of one size and dtype, got {first.shape} {first.dtype} and {f.shape} {f.dtype}")
    top = full_scale(first.dtype, bit_depth)
    dark = [f for f in frames if np.median(f) < DARK_SHARE * top]
    if not dark:
        return None
    return int(np.rint(np.median(np.stack(dark)))), len(dark)
