"""Residual-interpolation demosaicking guided by an edge-aware intensity image (numpy / OpenCV).

The method of Morimatsu et al., "Monochrome and color polarization demosaicking using edge-aware residual
interpolation" (ICIP 2020, "EARI"), in a form that runs at frame rate:

1. Guide: the unpolarized intensity ``I = S0 / 2`` at every pixel, as a weighted mean of four directional
   estimates (north, south, west, east: each the mean of the two 2x2 superpixels on that side, which hold all
   four polarizer angles and so are free of polarization modulation). Each estimate is weighted by the inverse
   of the intensity change on its side (a 3x5 mean of a modulation-free second difference), so the guide takes
   its value from the side of an edge the pixel is on.
2. Residual interpolation, per polarizer channel, on that channel's own samples (a quarter of the pixels, in
   half-resolution coordinates): a local linear model ``channel ~ a * guide`` fitted on Laplacians over 3x3
   sample windows (minimized-Laplacian RI, as in EARI), ``a`` averaged over the same window; then the channel
   is ``up(a) * I + up(channel - a * guide)`` at full resolution, where ``up`` is the bilinear interpolation of
   the sparse samples (the bilinear method's filter). Samples are kept exactly; with ``a = 0`` this is
   bilinear; with the true ``a`` fine intensity detail of the guide is carried into every channel, which is
   what removes bilinear's false polarization at edges.

Because ``up`` is linear, (S0, S1, S2) are computed directly (six 3x3 filters) like ``bilinear_stokes``.
The local-model offset ``b`` of the guided filter cancels out of the result and is not computed.

Borders: every full-resolution filter mirrors with REFLECT_101, which keeps each mirrored pixel's polarizer
angle; half-resolution filters run on one channel's samples, where REFLECT_101 needs no phase care.
Conventions (layout, order 0/45/90/135, units): ``conventions.py``. The torch twin is ``torch_ops.py``;
both must follow the constants and filter definitions here.
"""

from __future__ import annotations

import cv2
import numpy as np

from .conventions import POLARIZER_ANGLES_DEG, MosaicLayout

# The same as demosaic.BILINEAR_KERNEL and demosaic.BORDER (this module cannot import demosaic, which
# registers it): bilinear interpolation of a zero-filled channel; a mirror that keeps the mosaic phase.
BILINEAR_KERNEL = np.array([[1, 2, 1], [2, 4, 2], [1, 2, 1]], dtype=np.float32) / 4
BORDER = cv2.BORDER_REFLECT_101

GUIDE_EPS = 1e-3
"""Added to the directional intensity change (full-scale units) before inverting it into a weight: below
about a quarter 8-bit code, changes count as flat and the four directions are averaged evenly."""
RI_EPS = 1e-4
"""Regularisation of the Laplacian regression (full scale squared): where the guide has no local structure
``a`` goes to 0 and the channel to its bilinear interpolation."""
RI_RADIUS = 1
"""Half-width of the regression window in a channel's own samples (3x3 samples = 6x6 pixels)."""
A_RANGE = (0.0, 2.0)
"""Physical range of ``a`` (a polarizer passes between 0 and 2 times the mean intensity); clipping keeps noise
and extreme float input from extrapolating."""

GUIDE_PAD = 3
"""Pixels of mirrored mosaic (REFLECT_101) around the frame that the guide's filters reach."""
SMOOTH_1X3 = np.array([[1, 2, 1]], dtype=np.float32) / 8
"""Half the mean of a 2x2-superpixel pair: (SMOOTH_1X3 on rows -1 and 0) = mean of the two blocks north."""
SECOND_DIFF_1X3 = np.array([[-0.5, 1, -0.5]], dtype=np.float32)
"""Second difference along a row; it is the same on rows -1 and 0 for a constant-Stokes scene, so their
difference sees only intensity change (the modulation cancels)."""
LAPLACIAN = np.array([[0, -1, 0], [-1, 4, -1], [0, -1, 0]], dtype=np.float32)
"""Laplacian in a channel's half-resolution samples (a step-2 Laplacian of the mosaic)."""


def _filter(image: np.ndarray, kernel: np.ndarray) -> np.ndarray:
    return cv2.filter2D(image, cv2.CV_32F, kernel, borderType=BORDER)


def _box(image: np.ndarray) -> np.ndarray:
    k = 2 * RI_RADIUS + 1
    return cv2.boxFilter(image, cv2.CV_32F, (k, k), normalize=True, borderType=BORDER)


def intensity_guide(mosaic: np.ndarray) -> np.ndarray:
    """Edge-aware unpolarized intensity ``S0 / 2`` (H, W) float32 of a full-scale mosaic (step 1 above).

    With ``t`` the row filter SMOOTH_1X3 and ``e(y) = |d(y-1) - d(y)|`` for the row filter SECOND_DIFF_1X3
    ``d``, on the mosaic mirrored by GUIDE_PAD pixels: north estimate ``t(y-1) + t(y)``, south ``t(y) + t(y+1)``;
    north change = mean of ``e`` over rows y-2..y, columns x-2..x+2; south over rows y+1..y+3 (west and east
    the same on columns). Weights are ``1 / (change + GUIDE_EPS)``.
    """
    h, w = mosaic.shape
    p = GUIDE_PAD
    padded = cv2.copyMakeBorder(mosaic, p, p, p, p, BORDER)

    def at(image: np.ndarray, dy: int, dx: int) -> np.ndarray:
        return image[p + dy:p + dy + h, p + dx:p + dx + w]

    # cv2 element-wise operations: about twice as fast as numpy's on a full frame (threaded)
    num = np.zeros((h, w), dtype=np.float32)
    den = np.zeros((h, w), dtype=np.float32)
    for axis in (0, 1):  # 0: north/south (filters along rows, pairs of rows); 1: west/east
        smooth = SMOOTH_1X3 if axis == 0 else SMOOTH_1X3.T
        diff = SECOND_DIFF_1X3 if axis == 0 else SECOND_DIFF_1X3.T
        t = _filter(padded, smooth)
        d = _filter(padded, diff)
        e = np.zeros_like(d)
        if axis == 0:
            e[1:] = cv2.absdiff(d[:-1], d[1:])
            change = cv2.boxFilter(e, cv2.CV_32F, (5, 3), normalize=True, borderType=BORDER)
        else:
            e[:, 1:] = cv2.absdiff(d[:, :-1], d[:, 1:])
            change = cv2.boxFilter(e, cv2.CV_32F, (3, 5), normalize=True, borderType=BORDER)
        for side in (-1, 1):
            dy, dx = (side, 0) if axis == 0 else (0, side)
            estimate = cv2.add(at(t, 0, 0), at(t, dy, dx))
            # the change on a side: the 3-wide window of e just beyond the pixel (e pairs pixels k-1, k)
            shift = -1 if side < 0 else 2
            weight = cv2.divide(1.0, cv2.add(at(change, shift * abs(dy), shift * abs(dx)), GUIDE_EPS))
            cv2.add(num, cv2.multiply(weight, estimate), dst=num)
            cv2.add(den, weight, dst=den)
    return cv2.divide(num, den)


def _slope(samples: np.ndarray, guide: np.ndarray) -> np.ndarray:
    """``a`` of the local model ``samples ~ a * guide`` (half resolution), fitted on Laplacians, averaged."""
    lap_p = _filter(samples, LAPLACIAN)
    lap_g = _filter(guide, LAPLACIAN)
    num = _box(lap_g * lap_p)
    den = np.maximum(_box(lap_g * lap_g), np.float32(0)) + np.float32(RI_EPS)
    return _box(np.clip(num / den, *A_RANGE))


def _fields(mosaic: np.ndarray, layout: MosaicLayout) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Guide (H, W), and the sparse fields ``a`` and ``channel - a * guide`` interleaved at their own sites."""
    guide = intensity_guide(mosaic)
    a_full = np.empty_like(mosaic, dtype=np.float32)
    r_full = np.empty_like(a_full)
    for angle in POLARIZER_ANGLES_DEG:
        r, c = layout.position(angle)
        p = np.ascontiguousarray(mosaic[r::2, c::2], dtype=np.float32)
        g = np.ascontiguousarray(guide[r::2, c::2])
        a = _slope(p, g)
        a_full[r::2, c::2] = a
        r_full[r::2, c::2] = p - a * g
    return guide, a_full, r_full


def _modulation(layout: MosaicLayout, height: int, width: int) -> tuple[np.ndarray, np.ndarray]:
    """(+1 at 0, -1 at 90 degrees) and (+1 at 45, -1 at 135 degrees), float32 (H, W): S1 and S2 weights."""
    angles = layout.angle_map(height, width)
    return ((angles == 0).astype(np.float32) - (angles == 90).astype(np.float32),
            (angles == 45).astype(np.float32) - (angles == 135).astype(np.float32))


def residual_intensities(mosaic: np.ndarray, layout: MosaicLayout) -> np.ndarray:
    """Four polarizer images (4, H, W) at 0, 45, 90, 135 degrees by residual interpolation."""
    guide, a_full, r_full = _fields(mosaic, layout)
    angles = layout.angle_map(*mosaic.shape)
    zero = np.float32(0)
    return np.stack([_filter(np.where(angles == t, a_full, zero), BILINEAR_KERNEL) * guide
                     + _filter(np.where(angles == t, r_full, zero), BILINEAR_KERNEL)
                     for t in POLARIZER_ANGLES_DEG])


def residual_stokes(mosaic: np.ndarray, layout: MosaicLayout, polarization: bool
                    ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
    """(S0, S1, S2) of the residual-interpolation demosaic; the channel sums are taken before the filters."""
    guide, a_full, r_full = _fields(mosaic, layout)
    half = BILINEAR_KERNEL * np.float32(0.5)
    s0 = _filter(a_full, half) * guide + _filter(r_full, half)
    if not polarization:
        return s0, None, None
    out = [s0]
    for m in _modulation(layout, *mosaic.shape):
        out.append(_filter(cv2.multiply(a_full, m), BILINEAR_KERNEL) * guide
                   + _filter(cv2.multiply(r_full, m), BILINEAR_KERNEL))
    return out[0], out[1], out[2]
