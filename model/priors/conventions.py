"""The project's one place for polarization conventions. Every function that takes or returns Stokes
parameters, AoLP or a mosaic points here.

Angles
    A polarizer (or AoLP) angle ``t`` is counted counter-clockwise from image right (+x, along a row)
    toward image up (row 0 is the top row), as the image is displayed. This is Mitsuba 3's ``stokes``
    convention (measured: docs/platform-facts.md) and that of polanalyser. Angles are in radians in code;
    config keys and layouts state degrees in their names (``angles_deg``).

Stokes vector (linear part)
    ``I(t) = 0.5 * (S0 + S1*cos(2t) + S2*sin(2t))`` is what a pixel behind a polarizer at ``t`` measures, so
    ``S0 = (I0 + I45 + I90 + I135) / 2``, ``S1 = I0 - I90``, ``S2 = I45 - I135``.

Units
    Raw counts are normalised to full scale: 1.0 is the largest code of the stated bit depth, so
    ``I(t)`` is in [0, 1], ``S0`` in [0, 2] and ``S1``, ``S2`` in [-1, 1] for physical input.

Derived priors
    intensity  unpolarized intensity ``S0 / 2`` (the mean of the four polarizer images), in [0, 1].
    dolp       ``sqrt(S1^2 + S2^2) / S0`` clipped to [0, 1]; 0 where ``S0 <= DARK_S0`` (undefined there).
    aolp       ``0.5 * atan2(S2, S1)`` wrapped to [0, pi); 0 where ``|(S1, S2)| <= MIN_S12`` (undefined).
               AoLP has period pi: average and compare it on the circle, or use ``(cos 2*aolp, sin 2*aolp)``
               (keys ``aolp_cos``, ``aolp_sin``), which is how networks see it.
    atan2 is OpenCV's polynomial (``cv2.phase``, max error 1.7e-4 rad on 2*aolp); the torch path uses the
    same polynomial so both paths agree to 1e-5.

Mosaic
    A 2x2 superpixel of polarizer angles repeats over the sensor; ``MosaicLayout.angles_deg[r][c]`` is the
    angle at row ``r % 2``, column ``c % 2``. The default is the Sony IMX250MZR's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

CONVENTION_VERSION = 1
"""Bumped whenever anything in this module's docstring changes meaning; stored with models and datasets."""

DARK_S0 = 1e-6
"""S0 (full-scale units) at or below which a pixel is dark: DoLP is 0 there, not NaN."""

MIN_S12 = 1e-12
"""|(S1, S2)| (full-scale units) at or below which AoLP is undefined and reported as 0: far below one code of a
16-bit sensor, and above float32 underflow of S1^2 + S2^2, which would break cos^2 + sin^2 = 1."""

POLARIZER_ANGLES_DEG = (0, 45, 90, 135)
"""Order of the four polarizer images everywhere in the project (``demosaic`` returns them so)."""


@dataclass(frozen=True)
class MosaicLayout:
    """2x2 arrangement of on-chip polarizers; ``angles_deg[r][c]`` at row ``r % 2``, column ``c % 2``."""

    name: str
    angles_deg: tuple[tuple[int, int], tuple[int, int]]

    def __post_init__(self) -> None:
        flat = sorted(a for row in self.angles_deg for a in row)
        if flat != sorted(POLARIZER_ANGLES_DEG):
            raise ValueError(
                f"mosaic layout {self.name!r}: angles_deg must hold 0, 45, 90 and 135 once each, "
                f"got {self.angles_deg}"
            )

    def position(self, angle_deg: int) -> tuple[int, int]:
        """(row, col) in the 2x2 superpixel of the polarizer at ``angle_deg``."""
        for r in range(2):
            for c in range(2):
                if self.angles_deg[r][c] == angle_deg:
                    return r, c
        raise ValueError(f"mosaic layout {self.name!r} has no {angle_deg} degree polarizer")

    def angle_map(self, height: int, width: int) -> np.ndarray:
        """Polarizer angle in degrees of every pixel of a ``height`` x ``width`` mosaic (int16)."""
        cell = np.array(self.angles_deg, dtype=np.int16)
        return np.tile(cell, ((height + 1) // 2, (width + 1) // 2))[:height, :width]


IMX250MZR = MosaicLayout("imx250mzr", ((90, 45), (135, 0)))
"""Sony IMX250MZR / IMX253MZR (LUCID Phoenix/Triton, FLIR Blackfly S polarized): (0,0)=90, (0,1)=45,
(1,0)=135, (1,1)=0 degrees, as in polanalyser."""

LAYOUTS: dict[str, MosaicLayout] = {IMX250MZR.name: IMX250MZR}


def get_layout(layout: str | MosaicLayout) -> MosaicLayout:
    """A layout by name (see ``LAYOUTS``) or a ``MosaicLayout`` passed through."""
    if isinstance(layout, MosaicLayout):
        return layout
    try:
        return LAYOUTS[layout]
    except KeyError:
        raise ValueError(f"unknown mosaic layout {layout!r}; known: {', '.join(LAYOUTS)}") from None


MAX_BIT_DEPTH = 16
"""The most significant bits a raw code may have: the widest raw mosaic is uint16."""


def is_bit_depth(value: object) -> bool:
    """Whether ``value`` (read from a file: any JSON value) is a bit depth a raw mosaic can have: an int in
    1..``MAX_BIT_DEPTH`` (not a bool)."""
    return isinstance(value, int) and not isinstance(value, bool) and 1 <= value <= MAX_BIT_DEPTH


def full_scale(dtype: np.dtype, bit_depth: int | None = None) -> float:
    """Largest code of a raw mosaic: ``2**bit_depth - 1`` for integers (bit depth defaults to the dtype's
    width), 1.0 for floats (already in full-scale units)."""
    dtype = np.dtype(dtype)
    if np.issubdtype(dtype, np.floating):
        return 1.0
    if dtype not in (np.uint8, np.uint16):
        raise TypeError(f"raw mosaic dtype must be uint8, uint16 or float, got {dtype}")
    bits = bit_depth if bit_depth is not None else dtype.itemsize * 8
    if not 1 <= bits <= dtype.itemsize * 8:
        raise ValueError(f"bit depth {bits} does not fit dtype {dtype}")
    return float(2**bits - 1)
