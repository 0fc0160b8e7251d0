"""The priors core in torch: the same numbers as the numpy path (to 1e-5 full scale), on any device, batched.

Every function takes tensors of shape (H, W) or (N, H, W) and keeps the batch axis; the device is the input's,
and nothing is copied to the host (counts come back as 0-dim tensors, so the caller decides when to sync).
Definitions, constants and borders follow the numpy modules exactly: normalisation ``mosaic.py``, demosaicking
``demosaic.py`` and ``residual.py`` (REFLECT_101 borders, which keep the polarizer angle of mirrored pixels),
priors ``stokes.py`` (including OpenCV's polynomial atan2 behind ``cv2.phase``). Conventions:
``conventions.py``.

This module imports torch; ``model.priors`` itself does not import it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import torch
import torch.nn.functional as F

from . import residual
from .api import check_prior_names, needs_polarization
from .conventions import DARK_S0, MIN_S12, POLARIZER_ANGLES_DEG, MosaicLayout, full_scale, get_layout
from .demosaic import BILINEAR_KERNEL, METHODS

TorchStokes = tuple[torch.Tensor, torch.Tensor | None, torch.Tensor | None]

_FLOAT_DTYPES = (torch.float16, torch.bfloat16, torch.float32, torch.float64)
_NUMPY_DTYPE = {torch.uint8: np.uint8, torch.uint16: np.uint16}

# OpenCV's atan2 (core/src/mathfuncs_core.simd.hpp, fastAtan32): a degree-7 polynomial in degrees.
_ATAN2_DEG_PER_RAD = np.float32(180 / math.pi)
ATAN2_P1 = float(np.float32(0.9997878412794807) * _ATAN2_DEG_PER_RAD)
ATAN2_P3 = float(np.float32(-0.3258083974640975) * _ATAN2_DEG_PER_RAD)
ATAN2_P5 = float(np.float32(0.1555786518463281) * _ATAN2_DEG_PER_RAD)
ATAN2_P7 = float(np.float32(-0.04432655554792128) * _ATAN2_DEG_PER_RAD)
_ATAN2_EPS = float(np.float32(np.finfo(np.float64).eps))  # (float)DBL_EPSILON
_RAD_PER_DEG = float(np.float32(math.pi / 180))
_PI_F32 = float(np.float32(np.pi))


@dataclass(frozen=True)
class NormalizedMosaicTorch:
    """A mosaic batch (N, H, W) float32 in full-scale units and what was wrong with the input, as in
    ``mosaic.NormalizedMosaic``. Counts are 0-dim int64 tensors on the input's device; ``invalid`` (N, H, W)
    bool marks NaN/Inf or clipped pixels, None when the input type cannot hold any (integers at full width)."""

    data: torch.Tensor
    n_nonfinite: torch.Tensor
    n_out_of_range: torch.Tensor
    n_saturated: torch.Tensor
    invalid: torch.Tensor | None


def check_mosaic_tensor(raw: torch.Tensor) -> None:
    """Raise naming the shape or dtype unless ``raw`` is (H, W) or (N, H, W) with even sides."""
    if not isinstance(raw, torch.Tensor):
        raise TypeError(f"raw mosaic must be a torch tensor, got {type(raw).__name__}")
    if raw.ndim not in (2, 3):
        raise ValueError(f"raw mosaic tensor must be (H, W) or (N, H, W), got shape {tuple(raw.shape)}")
    h, w = raw.shape[-2:]
    if h < 2 or w < 2 or h % 2 or w % 2:
        raise ValueError(f"raw mosaic sides must be even and >= 2 (whole 2x2 superpixels), got shape "
                         f"{tuple(raw.shape)}")
    if raw.dtype not in _NUMPY_DTYPE and raw.dtype not in _FLOAT_DTYPES:
        raise TypeError(f"raw mosaic dtype must be uint8, uint16 or float, got {raw.dtype}")


def normalize_mosaic_torch(raw: torch.Tensor, bit_depth: int | None = None) -> NormalizedMosaicTorch:
    """(N, H, W) float32 full-scale mosaic from a raw (H, W) or (N, H, W) tensor; the rules of
    ``mosaic.normalize_mosaic``: integer codes above ``2**bit_depth - 1`` clipped and counted; float input
    taken as full scale, NaN/Inf -> 0 and outside [0, 1] clipped to it, both counted."""
    check_mosaic_tensor(raw)
    batch = raw if raw.ndim == 3 else raw.unsqueeze(0)
    if batch.dtype in _FLOAT_DTYPES:
        data = batch.to(torch.float32, copy=True)  # float64 beyond float32 range becomes Inf, as in numpy
        nonfinite = ~torch.isfinite(data)
        data = torch.where(nonfinite, torch.zeros((), dtype=data.dtype, device=data.device), data)
        out_of_range = (data < 0.0) | (data > 1.0)
        data = data.clamp(0.0, 1.0)
        return NormalizedMosaicTorch(data, nonfinite.sum(), out_of_range.sum(), (data >= 1.0).sum(),
                                     nonfinite | out_of_range)
    fs = full_scale(_NUMPY_DTYPE[batch.dtype], bit_depth)
    codes = batch.to(torch.int32)  # uint16 has few kernels in torch; int32 holds every code
    invalid = None
    n_out = torch.zeros((), dtype=torch.int64, device=batch.device)
    if fs < np.iinfo(_NUMPY_DTYPE[batch.dtype]).max:
        invalid = codes > int(fs)
        n_out = invalid.sum()
        codes = codes.clamp(max=int(fs))
    n_saturated = (codes >= int(fs)).sum()
    # a float32 division rounds like OpenCV's scaling (checked on every 8-, 12- and 16-bit code)
    return NormalizedMosaicTorch(codes.to(torch.float32) / float(fs), torch.zeros_like(n_out), n_out,
                                 n_saturated, invalid)


# ---------------------------------------------------------------------------------------------- filters

def _reflect101(p: int, n: int) -> int:
    """OpenCV's borderInterpolate for BORDER_REFLECT_101 (any distance, any size)."""
    if n == 1:
        return 0
    while p < 0 or p >= n:
        p = -p if p < 0 else 2 * n - p - 2
    return p


@lru_cache(maxsize=64)
def _index(n: int, before: int, after: int, device: torch.device) -> torch.Tensor:
    return torch.tensor([_reflect101(p, n) for p in range(-before, n + after)], dtype=torch.long, device=device)


def pad_reflect101(x: torch.Tensor, top: int, bottom: int, left: int, right: int) -> torch.Tensor:
    """Mirror (..., H, W) about the edge pixels (REFLECT_101 = torch's 'reflect'), any pad width."""
    h, w = x.shape[-2:]
    if max(top, bottom) < h and max(left, right) < w:
        shape = x.shape
        flat = x.reshape(-1, 1, h, w)
        return F.pad(flat, (left, right, top, bottom), mode="reflect").reshape(*shape[:-2], h + top + bottom,
                                                                               w + left + right)
    x = x.index_select(-2, _index(h, top, bottom, x.device))
    return x.index_select(-1, _index(w, left, right, x.device))


def filter2d(x: torch.Tensor, kernel: np.ndarray) -> torch.Tensor:
    """``cv2.filter2D(x, CV_32F, kernel, borderType=BORDER_REFLECT_101)`` on (..., H, W): correlation, anchor
    at the kernel's centre.

    A sum of shifted slices over the kernel's non-zero taps rather than ``conv2d``: the kernels here are tiny,
    the result does not depend on a backend, and cuDNN's default TF32 (10-bit mantissa) cannot creep in.
    """
    kernel = np.asarray(kernel, dtype=np.float32)
    kh, kw = kernel.shape
    h, w = x.shape[-2:]
    padded = pad_reflect101(x, kh // 2, kh - 1 - kh // 2, kw // 2, kw - 1 - kw // 2)
    out = None
    for i in range(kh):
        for j in range(kw):
            tap = float(kernel[i, j])
            if tap == 0.0:
                continue
            window = padded[..., i:i + h, j:j + w]
            out = window * tap if out is None else out.add_(window, alpha=tap)
    return out if out is not None else torch.zeros_like(x)


def box_filter(x: torch.Tensor, width: int, height: int) -> torch.Tensor:
    """``cv2.boxFilter`` (normalised, centred, BORDER_REFLECT_101) with a ``width`` x ``height`` window,
    as a row pass then a column pass."""
    rows = filter2d(x, np.ones((1, width), dtype=np.float32))
    return filter2d(rows, np.ones((height, 1), dtype=np.float32)) * (1.0 / (width * height))


# ---------------------------------------------------------------------------------------------- demosaic

@lru_cache(maxsize=16)
def _angle_map(layout: MosaicLayout, height: int, width: int, device: torch.device) -> torch.Tensor:
    return torch.from_numpy(layout.angle_map(height, width).astype(np.int16)).to(device)


def _modulation(layout: MosaicLayout, height: int, width: int, device: torch.device
                ) -> tuple[torch.Tensor, torch.Tensor]:
    angles = _angle_map(layout, height, width, device)
    m1 = (angles == 0).to(torch.float32) - (angles == 90).to(torch.float32)
    m2 = (angles == 45).to(torch.float32) - (angles == 135).to(torch.float32)
    return m1, m2


def intensities_to_stokes_torch(images: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
    """(S0, S1, S2) from four polarizer images stacked on axis 0 (0, 45, 90, 135 degrees)."""
    i0, i45, i90, i135 = images[0], images[1], images[2], images[3]
    return (i0 + i45 + i90 + i135) * 0.5, i0 - i90, i45 - i135


def bilinear_intensities_torch(mosaic: torch.Tensor, layout: MosaicLayout) -> torch.Tensor:
    """(4, N, H, W) bilinear polarizer images; see ``demosaic.bilinear_intensities``."""
    angles = _angle_map(layout, *mosaic.shape[-2:], mosaic.device)
    zero = torch.zeros((), dtype=mosaic.dtype, device=mosaic.device)
    return torch.stack([filter2d(torch.where(angles == a, mosaic, zero), BILINEAR_KERNEL)
                        for a in POLARIZER_ANGLES_DEG])


def bilinear_stokes_torch(mosaic: torch.Tensor, layout: MosaicLayout, polarization: bool) -> TorchStokes:
    """See ``demosaic.bilinear_stokes``."""
    s0 = filter2d(mosaic, BILINEAR_KERNEL * np.float32(0.5))
    if not polarization:
        return s0, None, None
    m1, m2 = _modulation(layout, *mosaic.shape[-2:], mosaic.device)
    return s0, filter2d(mosaic * m1, BILINEAR_KERNEL), filter2d(mosaic * m2, BILINEAR_KERNEL)


def superpixel_intensities_torch(mosaic: torch.Tensor, layout: MosaicLayout) -> torch.Tensor:
    """(4, N, H/2, W/2) polarizer images, one per 2x2 superpixel."""
    return torch.stack([mosaic[..., r::2, c::2] for r, c in (layout.position(a) for a in POLARIZER_ANGLES_DEG)])


def intensity_guide_torch(mosaic: torch.Tensor) -> torch.Tensor:
    """Edge-aware intensity ``S0 / 2`` (N, H, W); see ``residual.intensity_guide``."""
    h, w = mosaic.shape[-2:]
    p = residual.GUIDE_PAD
    padded = pad_reflect101(mosaic, p, p, p, p)

    def at(image: torch.Tensor, dy: int, dx: int) -> torch.Tensor:
        return image[..., p + dy:p + dy + h, p + dx:p + dx + w]

    num = torch.zeros_like(mosaic)
    den = torch.zeros_like(mosaic)
    for axis in (0, 1):
        smooth = residual.SMOOTH_1X3 if axis == 0 else residual.SMOOTH_1X3.T
        diff = residual.SECOND_DIFF_1X3 if axis == 0 else residual.SECOND_DIFF_1X3.T
        t = filter2d(padded, smooth)
        d = filter2d(padded, diff)
        e = torch.zeros_like(d)
        if axis == 0:
            e[..., 1:, :] = (d[..., :-1, :] - d[..., 1:, :]).abs()
            change = box_filter(e, 5, 3)
        else:
            e[..., :, 1:] = (d[..., :, :-1] - d[..., :, 1:]).abs()
            change = box_filter(e, 3, 5)
        for side in (-1, 1):
            dy, dx = (side, 0) if axis == 0 else (0, side)
            estimate = at(t, 0, 0) + at(t, dy, dx)
            shift = -1 if side < 0 else 2
            weight = 1.0 / (at(change, shift * abs(dy), shift * abs(dx)) + residual.GUIDE_EPS)
            num = num + weight * estimate
            den = den + weight
    return num / den


def _slope_torch(samples: torch.Tensor, guide: torch.Tensor) -> torch.Tensor:
    k = 2 * residual.RI_RADIUS + 1
    lap_p = filter2d(samples, residual.LAPLACIAN)
    lap_g = filter2d(guide, residual.LAPLACIAN)
    num = box_filter(lap_g * lap_p, k, k)
    den = box_filter(lap_g * lap_g, k, k).clamp(min=0) + residual.RI_EPS
    return box_filter((num / den).clamp(*residual.A_RANGE), k, k)


def _fields_torch(mosaic: torch.Tensor, layout: MosaicLayout) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
    guide = intensity_guide_torch(mosaic)
    a_full = torch.empty_like(mosaic)
    r_full = torch.empty_like(mosaic)
    for angle in POLARIZER_ANGLES_DEG:
        r, c = layout.position(angle)
        p = mosaic[..., r::2, c::2]
        g = guide[..., r::2, c::2]
        a = _slope_torch(p, g)
        a_full[..., r::2, c::2] = a
        r_full[..., r::2, c::2] = p - a * g
    return guide, a_full, r_full


def residual_intensities_torch(mosaic: torch.Tensor, layout: MosaicLayout) -> torch.Tensor:
    """(4, N, H, W) polarizer images by residual interpolation; see ``residual.residual_intensities``."""
    guide, a_full, r_full = _fields_torch(mosaic, layout)
    angles = _angle_map(layout, *mosaic.shape[-2:], mosaic.device)
    zero = torch.zeros((), dtype=mosaic.dtype, device=mosaic.device)
    return torch.stack([filter2d(torch.where(angles == t, a_full, zero), BILINEAR_KERNEL) * guide
                        + filter2d(torch.where(angles == t, r_full, zero), BILINEAR_KERNEL)
                        for t in POLARIZER_ANGLES_DEG])


def residual_stokes_torch(mosaic: torch.Tensor, layout: MosaicLayout, polarization: bool) -> TorchStokes:
    """See ``residual.residual_stokes``."""
    guide, a_full, r_full = _fields_torch(mosaic, layout)
    half = BILINEAR_KERNEL * np.float32(0.5)
    s0 = filter2d(a_full, half) * guide + filter2d(r_full, half)
    if not polarization:
        return s0, None, None
    m1, m2 = _modulation(layout, *mosaic.shape[-2:], mosaic.device)
    s1 = filter2d(a_full * m1, BILINEAR_KERNEL) * guide + filter2d(r_full * m1, BILINEAR_KERNEL)
    s2 = filter2d(a_full * m2, BILINEAR_KERNEL) * guide + filter2d(r_full * m2, BILINEAR_KERNEL)
    return s0, s1, s2


TORCH_METHODS = {
    "bilinear": (bilinear_intensities_torch, bilinear_stokes_torch),
    "superpixel": (superpixel_intensities_torch, None),
    "residual": (residual_intensities_torch, residual_stokes_torch),
}
"""Registry names as ``demosaic.METHODS``: (intensities, direct Stokes path or None)."""


def _get(method: str):
    if method not in TORCH_METHODS:
        known = ", ".join(sorted(set(METHODS) | set(TORCH_METHODS)))
        raise ValueError(f"unknown demosaic method {method!r} for the torch path; known: {known}")
    return TORCH_METHODS[method]


def demosaic_torch(mosaic: torch.Tensor, layout: str | MosaicLayout = "imx250mzr", method: str = "bilinear"
                   ) -> torch.Tensor:
    """Four polarizer images (4, ..., H', W') at 0, 45, 90, 135 degrees from a full-scale float32 mosaic
    (H, W) or (N, H, W)."""
    batch = mosaic if mosaic.ndim == 3 else mosaic.unsqueeze(0)
    out = _get(method)[0](batch, get_layout(layout))
    return out if mosaic.ndim == 3 else out[:, 0]


def mosaic_to_stokes_torch(mosaic: torch.Tensor, layout: str | MosaicLayout = "imx250mzr",
                           method: str = "bilinear", polarization: bool = True) -> TorchStokes:
    """(S0, S1, S2) from a full-scale float32 mosaic (N, H, W); S1, S2 None unless ``polarization``."""
    intensities, stokes = _get(method)
    lay = get_layout(layout)
    if stokes is not None:
        return stokes(mosaic, lay, polarization)
    s0, s1, s2 = intensities_to_stokes_torch(intensities(mosaic, lay))
    return (s0, s1, s2) if polarization else (s0, None, None)


# ---------------------------------------------------------------------------------------------- priors

def unpolarized_intensity_torch(s0: torch.Tensor) -> torch.Tensor:
    """``S0 / 2``, full-scale units."""
    return s0 * 0.5


def dolp_torch(s0: torch.Tensor, s1: torch.Tensor, s2: torch.Tensor) -> torch.Tensor:
    """``sqrt(S1^2 + S2^2) / S0`` in [0, 1]; 0 where ``S0 <= DARK_S0``. See ``stokes.dolp``."""
    mag = torch.sqrt(s1 * s1 + s2 * s2)
    out = (mag / s0.clamp(min=DARK_S0)).clamp(max=1.0)
    return torch.where(s0 <= DARK_S0, torch.zeros((), dtype=out.dtype, device=out.device), out)


def phase_torch(x: torch.Tensor, y: torch.Tensor) -> torch.Tensor:
    """``cv2.phase(x, y)``: the angle of (x, y) in radians in [0, 2pi], by OpenCV's polynomial atan2 (max error
    about 0.01 degrees), so that both paths give the same AoLP. -0.0 counts as +0.0, as in OpenCV."""
    ax, ay = x.abs(), y.abs()
    c = torch.minimum(ax, ay) / (torch.maximum(ax, ay) + _ATAN2_EPS)
    c2 = c * c
    a = (((ATAN2_P7 * c2 + ATAN2_P5) * c2 + ATAN2_P3) * c2 + ATAN2_P1) * c
    a = torch.where(ax >= ay, a, 90.0 - a)
    a = torch.where(x < 0, 180.0 - a, a)
    a = torch.where(y < 0, 360.0 - a, a)
    return a * _RAD_PER_DEG


def aolp_torch(s1: torch.Tensor, s2: torch.Tensor) -> torch.Tensor:
    """``0.5 * atan2(S2, S1)`` in [0, pi); 0 where ``|(S1, S2)| <= MIN_S12``. See ``stokes.aolp``."""
    out = phase_torch(s1, s2) * 0.5
    undefined = (out >= _PI_F32) | (torch.sqrt(s1 * s1 + s2 * s2) <= MIN_S12)
    return torch.where(undefined, torch.zeros((), dtype=out.dtype, device=out.device), out)


def aolp_vector_torch(s1: torch.Tensor, s2: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    """``(cos 2*aolp, sin 2*aolp)``; (1, 0) where ``|(S1, S2)| <= MIN_S12``. See ``stokes.aolp_vector``."""
    mag = torch.sqrt(s1 * s1 + s2 * s2)
    undefined = mag <= MIN_S12
    mag = torch.where(undefined, torch.ones((), dtype=mag.dtype, device=mag.device), mag)
    cos2 = torch.where(undefined, 1.0, s1 / mag)
    sin2 = torch.where(undefined, 0.0, s2 / mag)
    return cos2, sin2


def priors_from_stokes_torch(names, s0: torch.Tensor, s1: torch.Tensor | None, s2: torch.Tensor | None
                             ) -> dict[str, torch.Tensor]:
    """The requested priors plus the Stokes images, as ``api.priors_from_stokes``."""
    names = set(names)
    out: dict[str, torch.Tensor] = {"s0": s0}
    if s1 is not None and s2 is not None:
        out["s1"], out["s2"] = s1, s2
    if "intensity" in names:
        out["intensity"] = unpolarized_intensity_torch(s0)
    if "dolp" in names:
        out["dolp"] = dolp_torch(s0, s1, s2)
    if "aolp" in names:
        out["aolp"] = aolp_torch(s1, s2)
    if "aolp_cos" in names or "aolp_sin" in names:
        out["aolp_cos"], out["aolp_sin"] = aolp_vector_torch(s1, s2)
    return out


def compute_priors_torch(raw: torch.Tensor, layout: str | MosaicLayout = "imx250mzr", method: str = "bilinear",
                         priors=("intensity", "dolp", "aolp"), bit_depth: int | None = None
                         ) -> dict[str, torch.Tensor]:
    """``model.priors.compute_priors`` for a tensor: raw (H, W) or (N, H, W) uint8/uint16/float on any device
    -> dict of float32 tensors (H', W') or (N, H', W') with the same keys and values (to 1e-5 full scale).

    Input problems are not reported here; call ``normalize_mosaic_torch`` for the counts and mask.
    """
    names = check_prior_names(priors)
    _get(method)
    mosaic = normalize_mosaic_torch(raw, bit_depth).data
    s0, s1, s2 = mosaic_to_stokes_torch(mosaic, layout, method, needs_polarization(names))
    out = priors_from_stokes_torch(names, s0, s1, s2)
    return out if raw.ndim == 3 else {k: v[0] for k, v in out.items()}
