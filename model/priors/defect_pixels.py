"""A sensor's defective pixels: finding them in a stack of frames, and filling them from their neighbours.

A pixel stuck bright (hot) or dark (dead) reads the same whatever the light. On a polarization mosaic a pixel's
nearest neighbours sit behind other polarizer angles, so a camera's own defect-pixel correction, made for a plain
mono sensor, may be off or mix the angles. The station fills the pixels of a map itself, before the demosaic.

Convention: a map is a bool (H, W) array on the frame's pixel grid (True: defective), the camera's region of interest
as it streams; on disk a PNG of that size whose non-zero pixels are defective. A pixel is filled only from pixels of
its own polarizer angle: the eight 2 px away along its row, column and diagonals (``SAME_ANGLE``), so the mosaic's
2x2 layout is kept. Codes and full scale are the frame's (``model.priors.conventions.full_scale``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .conventions import full_scale

SAME_ANGLE = ((-2, -2), (-2, 0), (-2, 2), (0, -2), (0, 2), (2, -2), (2, 0), (2, 2))
"""Offsets (dy, dx) of a mosaic pixel's nearest neighbours behind the same polarizer angle."""

MIN_STEP = 0.05
"""``find_defect_pixels``' default: a pixel is defective only if it stands this share of full scale from its
same-angle neighbours (as well as far outside the frame's spread). A pixel stuck at full scale in every frame made
the shipped model reject good parts; one 10 % of full scale too bright did not (docs/results/2026-12-02-spectral.md)."""

MAX_SHARE = 0.001
"""More than this share of the frame found defective means the frames were not suitable (the part's own edges,
a lit scene that moved): ``find_defect_pixels`` refuses rather than map them."""


def _neighbour_mean(raw: np.ndarray, valid: np.ndarray, ys: np.ndarray, xs: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Sum and count of the valid same-angle neighbours of pixels (ys, xs)."""
    h, w = raw.shape
    total = np.zeros(len(ys), np.float64)
    count = np.zeros(len(ys), np.int64)
    for dy, dx in SAME_ANGLE:
        y, x = ys + dy, xs + dx
        inside = (y >= 0) & (y < h) & (x >= 0) & (x < w)
        yi, xi = np.where(inside, y, 0), np.where(inside, x, 0)
        ok = inside & valid[yi, xi]
        total += np.where(ok, raw[yi, xi], 0)
        count += ok
    return total, count


@dataclass(frozen=True)
class DefectPixelMap:
    """A map with its pixels listed once (``where``: (K, 2) rows and columns), for filling frame after frame: the
    listing is a pass over the whole frame, the fill touches only the K pixels (and copies the frame)."""

    mask: np.ndarray
    where: np.ndarray

    @classmethod
    def of(cls, mask: np.ndarray) -> DefectPixelMap:
        return cls(mask, np.argwhere(mask))

    def fill(self, raw: np.ndarray) -> np.ndarray:
        """``fill_defect_pixels(raw, self.mask)``."""
        if self.mask.shape != raw.shape[:2] or raw.ndim != 2:
            raise ValueError(f"the defect pixel map is {self.mask.shape[1]}x{self.mask.shape[0]}, the frame "
                             f"{raw.shape[1] if raw.ndim > 1 else '?'}x{raw.shape[0]}: a map is made for one region "
                             f"of interest")
        if not len(self.where):
            return raw
        out = raw.copy()
        valid = ~self.mask
        todo = self.where
        for _ in range(3):
            if not len(todo):
                break
            ys, xs = todo[:, 0], todo[:, 1]
            total, count = _neighbour_mean(out, valid, ys, xs)
            done = count > 0
            value = total[done] / count[done]
            out[ys[done], xs[done]] = np.rint(value) if np.issubdtype(out.dtype, np.integer) else value
            valid[ys[done], xs[done]] = True
            todo = todo[~done]
        for y, x in todo:  # a cluster wider than three passes: its angle's median over the frame's good pixels
            same = np.zeros_like(self.mask)
            same[y % 2::2, x % 2::2] = True
            pool = out[same & ~self.mask]
            out[y, x] = np.median(pool) if pool.size else 0
        return out


def fill_defect_pixels(raw: np.ndarray, mask: np.ndarray | DefectPixelMap | None) -> np.ndarray:
    """``raw`` (H, W) mosaic (integer codes or float) with each pixel of ``mask`` (H, W bool, or a
    ``DefectPixelMap``) replaced by the mean of its same-angle neighbours that are not in the mask (rounded for
    integer codes). A pixel whose neighbours are all defective (a cluster) is filled in a later pass from those
    filled before it; after three passes, from the median of the frame's good pixels of its angle. Returns ``raw``
    itself when the mask is None or empty, else a copy. ValueError when the shapes differ (a map made for another
    region of interest)."""
    if mask is None:
        return raw
    return (mask if isinstance(mask, DefectPixelMap) else DefectPixelMap.of(mask)).fill(raw)


def find_defect_pixels(raws: Sequence[np.ndarray], bit_depth: int | None = None, *, min_step: float = MIN_STEP,
                       z: float = 8.0) -> np.ndarray:
    """Defective pixels of a sensor from frames of the same size: (H, W) bool.

    Each pixel's difference from the median of its same-angle neighbours, in full-scale units
    (``bit_depth``: significant bits of integer codes, default the dtype's), is taken in every frame, and its median
    over the frames kept. A pixel is defective where that median is at least ``min_step`` from 0 and ``z`` robust
    standard deviations (1.4826 MAD over the frame) from the frame's median of it. Frames with the lens capped find
    pixels stuck bright; frames of an evenly lit plain target find those stuck dark as well. Frames of parts work
    only where the scene's own fine detail moves between them; more than ``MAX_SHARE`` of the frame found raises
    ValueError (the frames do not suit)."""
    if not raws:
        raise ValueError("no frames to find defective pixels in")
    shape = raws[0].shape
    if len(shape) != 2 or any(r.shape != shape for r in raws):
        raise ValueError("frames of one size (H, W) are needed, one mosaic each")
    h, w = shape
    steps = []
    for raw in raws:
        fs = full_scale(raw.dtype, bit_depth) if np.issubdtype(raw.dtype, np.integer) else 1.0
        r = raw.astype(np.float64) / fs
        padded = np.pad(r, 2, mode="reflect")  # reflection by 2 keeps each pixel's angle (the 2x2 phase)
        stack = [padded[2 + dy:2 + dy + h, 2 + dx:2 + dx + w] for dy, dx in SAME_ANGLE]
        steps.append(r - np.median(np.stack(stack), axis=0))
    step = np.median(np.stack(steps), axis=0)
    centre = np.median(step)
    spread = 1.4826 * np.median(np.abs(step - centre))
    found = (np.abs(step) >= min_step) & (np.abs(step - centre) >= z * spread)
    share = found.mean()
    if share > MAX_SHARE:
        raise ValueError(f"{found.sum()} pixels ({100 * share:.2f} % of the frame) stand out from their neighbours: "
                         f"more than a sensor's defects ({100 * MAX_SHARE:g} %); use frames with the lens capped or "
                         f"of an evenly lit plain target")
    return found


def read_defect_pixel_map(path: str | Path) -> np.ndarray:
    """A map PNG -> (H, W) bool (non-zero: defective). ValueError naming the file when it is missing or not a
    single-channel image."""
    import cv2

    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{path}: no such file")
    img = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
    if img is None or img.ndim != 2:
        raise ValueError(f"{path}: not a single-channel PNG (a defect pixel map: non-zero pixels are defective)")
    return img > 0


def write_defect_pixel_map(path: str | Path, mask: np.ndarray) -> None:
    """(H, W) bool -> PNG, 255 on defective pixels."""
    import cv2

    if not cv2.imwrite(str(path), np.where(mask, 255, 0).astype(np.uint8)):
        raise ValueError(f"{path}: could not be written")
