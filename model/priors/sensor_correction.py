"""What the station undoes of a camera's sensor before the demosaic, in one place and one order.

Order: the black level first (``black_level``: codes taken away, full scale kept), then the defective pixels
(``defect_pixels``: filled from their same-angle neighbours, now in light units from zero). The station's frames
(``station.inspector``) and every set a command reads (``station.datasets.load_split``) go through the same
``SensorCorrection``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .black_level import subtract_black_level
from .defect_pixels import DefectPixelMap, fill_defect_pixels


@dataclass(frozen=True)
class SensorCorrection:
    """A camera's black level (codes of its frames; 0: none) and defect pixel map (listed once; None: none)."""

    black_level: int = 0
    defect_pixels: DefectPixelMap | None = None

    @classmethod
    def of(cls, black_level: int = 0, defect_pixels: np.ndarray | None = None) -> SensorCorrection:
        """From a black level and a (H, W) bool map as read from a file (None: no map)."""
        return cls(black_level, None if defect_pixels is None else DefectPixelMap.of(defect_pixels))

    def __call__(self, raw: np.ndarray, bit_depth: int | None = None) -> np.ndarray:
        """``raw`` corrected (``raw`` itself when there is nothing to correct); ValueError as the steps raise it (a
        black level not below full scale, a map of another size than the frame)."""
        return fill_defect_pixels(subtract_black_level(raw, self.black_level, bit_depth), self.defect_pixels)
