"""Stokes parameters and the priors derived from them (numpy, float32). Conventions: ``conventions.py``.

All functions are pure, accept arrays of any shape (float32 recommended; others are converted) and never
return NaN or Inf for finite input.
"""

from __future__ import annotations

import cv2
import numpy as np

from .conventions import DARK_S0, MIN_S12


def _f32_2d(a: np.ndarray) -> np.ndarray:
    """Contiguous float32 view with two dimensions, as OpenCV wants (scalars and 1-D become one row)."""
    a = np.ascontiguousarray(a, dtype=np.float32)
    return a.reshape(-1, a.shape[-1]) if a.ndim >= 1 else a.reshape(1, 1)


def intensities_to_stokes(images: np.ndarray) -> np.ndarray:
    """Linear Stokes (3, ...) = (S0, S1, S2) from four polarizer images (4, ...) at 0, 45, 90, 135 degrees.

    ``S0 = (I0 + I45 + I90 + I135) / 2``, ``S1 = I0 - I90``, ``S2 = I45 - I135``.
    """
    if images.shape[0] != 4:
        raise ValueError(f"expected 4 polarizer images on axis 0, got shape {images.shape}")
    i0, i45, i90, i135 = (images[k].astype(np.float32, copy=False) for k in range(4))
    return np.stack([(i0 + i45 + i90 + i135) * np.float32(0.5), i0 - i90, i45 - i135])


def stokes_to_intensity(s0: np.ndarray, angle_rad: float | np.ndarray, s1: np.ndarray, s2: np.ndarray
                        ) -> np.ndarray:
    """What a pixel behind a polarizer at ``angle_rad`` measures: ``0.5 * (S0 + S1 cos 2t + S2 sin 2t)``."""
    two_t = 2.0 * np.asarray(angle_rad, dtype=np.float64)
    return (0.5 * (s0 + s1 * np.cos(two_t) + s2 * np.sin(two_t))).astype(np.float32)


def unpolarized_intensity(s0: np.ndarray) -> np.ndarray:
    """Unpolarized intensity ``S0 / 2`` (mean of the four polarizer images), full-scale units."""
    return np.multiply(s0, np.float32(0.5), dtype=np.float32)


def dolp(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray) -> np.ndarray:
    """Degree of linear polarization ``sqrt(S1^2 + S2^2) / S0`` in [0, 1]; 0 where ``S0 <= DARK_S0``.

    Clipping at 1 is not cosmetic: sensor noise makes ``|S12| > S0`` in dark pixels.
    """
    shape = np.shape(s0)
    a0, a1, a2 = _f32_2d(s0), _f32_2d(s1), _f32_2d(s2)
    mag = cv2.magnitude(a1, a2)
    dark = a0 <= DARK_S0
    out = np.divide(mag, np.maximum(a0, np.float32(DARK_S0)))
    np.minimum(out, np.float32(1.0), out=out)
    out[dark] = 0.0
    return out.reshape(shape)


def aolp(s1: np.ndarray, s2: np.ndarray) -> np.ndarray:
    """Angle of linear polarization ``0.5 * atan2(S2, S1)`` in radians, in [0, pi); 0 where
    ``|(S1, S2)| <= MIN_S12`` (undefined)."""
    shape = np.shape(s1)
    a1, a2 = _f32_2d(s1), _f32_2d(s2)
    out = cv2.phase(a1, a2)  # [0, 2pi], OpenCV polynomial atan2 (see conventions)
    out *= np.float32(0.5)
    # 2pi - tiny rounds up to 2pi, which is angle 0 on the circle
    out[(out >= np.float32(np.pi)) | (cv2.magnitude(a1, a2) <= MIN_S12)] = 0.0
    return out.reshape(shape)


def aolp_vector(s1: np.ndarray, s2: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(cos 2*aolp, sin 2*aolp)`` without a trigonometric call; (1, 0) where ``|(S1, S2)| <= MIN_S12``."""
    shape = np.shape(s1)
    a1, a2 = _f32_2d(s1), _f32_2d(s2)
    mag = cv2.magnitude(a1, a2)
    undefined = mag <= MIN_S12
    mag[undefined] = 1.0
    cos2 = np.divide(a1, mag)
    sin2 = np.divide(a2, mag)
    cos2[undefined] = 1.0
    sin2[undefined] = 0.0
    return cos2.reshape(shape), sin2.reshape(shape)
