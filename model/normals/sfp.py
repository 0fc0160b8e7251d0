"""Physics-based shape from polarization (diffuse model) and the angular error of normal maps. Numpy only.

Conventions
    Camera frame: x image right, y image up, z toward the camera (the frame of the rendered ground-truth normals,
    ``sim.scene.camera_axes``, and of the ``normal`` prior in ``model.draem.config``). Pixel (row, col) has its
    centre at (col + 0.5, row + 0.5) in pixel-edge coordinates, row 0 on top.
    Viewing direction ``v``: the unit vector from the surface point seen in a pixel toward the camera. Pinhole
    camera with horizontal field of view ``fov_x_deg`` spanning the frame's full width (Mitsuba's ``fov_axis
    "x"``), square pixels, principal point at the frame centre: ``v = normalize(-u, -w, f)`` with ``u``, ``w`` the
    pixel centre's offsets from the frame centre (right, up) and ``f = (W / 2) / tan(fov_x / 2)`` in pixels.
    Without a field of view, orthographic: ``v = (0, 0, 1)`` everywhere.
    AoLP: radians in [0, pi), counter-clockwise from image right toward image up (``model.priors.conventions``),
    so the direction ``(cos a, sin a, 0)`` in the camera frame.
    Zenith ``theta``: the angle between the normal and ``v``; azimuth: the normal's direction around ``v``.

Diffuse polarization (Atkinson & Hancock 2006)
    Light scattered inside a dielectric of refractive index ``n`` leaves it partially polarized in the plane of
    emission (the plane through ``v`` and the normal), with degree
    ``rho(theta, n) = (n - 1/n)^2 sin^2 theta / (2 + 2 n^2 - (n + 1/n)^2 sin^2 theta + 4 cos theta sqrt(n^2 -
    sin^2 theta))``, which rises monotonically from 0 at theta = 0 to ``rho(90 deg)`` (0.385 for n = 1.5).
    So: zenith = rho^-1(DoLP) (a lookup table; DoLP above ``rho(90 deg)`` gives 90 degrees), and the normal's
    azimuth is the AoLP or the AoLP + pi (the pi ambiguity: the polarizer cannot tell the two apart).
    Perspective: the E-field direction is perpendicular to ``v`` and projects onto the image plane along the
    AoLP, so the azimuth direction is ``p = normalize(e - (e . v / v_z) z)`` with ``e = (cos a, sin a, 0)``, and
    ``normal = cos(theta) v +- sin(theta) p``. Orthographic (v = z): ``normal = (+-sin t cos a, +-sin t sin a,
    cos t)``.
    Not modelled: specular reflection (polarized perpendicular to the plane of incidence, AoLP off by 90 degrees,
    DoLP up to 1: highlights on plastic, all of a metal part), interreflections, noise bias of DoLP.

Pi ambiguity (``resolve``)
    "outward": the sign whose image-plane azimuth points away from a centre point (default: the centroid of the
    object mask, else the frame centre); right for convex objects seen from outside, wrong on concave parts and
    on flat faces crossing the centre, where half the face gets the mirrored normal. Both candidates face the
    camera (``n . v = cos theta >= 0``), so "facing the camera" cannot choose between them.
    "reference": the candidate closer to a given normal map (with the ground truth: an upper bound that isolates
    the zenith and azimuth error from the ambiguity).
"""

from __future__ import annotations

import functools

import numpy as np

from .errors import NormalsError

DEFAULT_IOR = 1.5
"""Refractive index of the part's dielectric (Mitsuba's ``pplastic`` default is 1.49, polypropylene)."""

LUT_SIZE = 4096


def view_directions(shape: tuple[int, int], fov_x_deg: float | None = None,
                    box: tuple[int, int, int, int] | None = None, size: int | tuple[int, int] | None = None
                    ) -> np.ndarray:
    """(h, w, 3) float32 unit viewing directions (surface toward camera) of a ``shape`` = (H, W) frame.

    ``box`` = (top, left, height, width) restricts them to a crop of the frame and ``size`` (side, or (h, w))
    resamples the crop to that grid (pixel centres spread evenly over the box, as bilinear resizing with
    ``align_corners=False`` places them); default: the whole frame at its own resolution. ``fov_x_deg`` None:
    orthographic, (0, 0, 1) everywhere."""
    H, W = int(shape[0]), int(shape[1])
    top, left, bh, bw = box if box is not None else (0, 0, H, W)
    if size is None:
        sh, sw = bh, bw
    elif isinstance(size, int):
        sh = sw = size
    else:
        sh, sw = size
    if min(H, W, bh, bw, sh, sw) < 1:
        raise NormalsError(f"view_directions: empty frame, box or size ({shape}, {box}, {size})")
    if fov_x_deg is None:
        out = np.zeros((sh, sw, 3), np.float32)
        out[..., 2] = 1
        return out
    if not 0 < fov_x_deg < 180:
        raise NormalsError(f"view_directions: fov_x_deg must be in (0, 180), got {fov_x_deg}")
    f = (W / 2) / np.tan(np.radians(fov_x_deg) / 2)
    x = left + (np.arange(sw) + 0.5) * (bw / sw)  # pixel-edge coordinates of the resampled pixel centres
    y = top + (np.arange(sh) + 0.5) * (bh / sh)
    u = np.broadcast_to(x[None, :] - W / 2, (sh, sw))  # right of the frame centre
    w = np.broadcast_to(H / 2 - y[:, None], (sh, sw))  # up from the frame centre
    v = np.stack([-u, -w, np.full((sh, sw), f)], -1)
    return (v / np.linalg.norm(v, axis=-1, keepdims=True)).astype(np.float32)


def diffuse_dolp(theta: np.ndarray | float, n: float = DEFAULT_IOR) -> np.ndarray:
    """DoLP of diffusely scattered light leaving a dielectric of refractive index ``n`` at zenith ``theta``
    (radians, [0, pi/2]); the forward model that ``zenith_from_dolp`` inverts."""
    if not n > 1:
        raise NormalsError(f"refractive index must be > 1, got {n}")
    t = np.asarray(theta, dtype=np.float64)
    s2 = np.sin(t) ** 2
    num = (n - 1 / n) ** 2 * s2
    den = 2 + 2 * n**2 - (n + 1 / n) ** 2 * s2 + 4 * np.cos(t) * np.sqrt(n**2 - s2)
    return num / den


@functools.lru_cache(maxsize=8)
def _zenith_lut(n: float, size: int) -> tuple[np.ndarray, np.ndarray]:
    """(sqrt(rho), theta) on a uniform theta grid over [0, pi/2]; sqrt(rho) ~ theta near 0, so linear
    interpolation in it stays exact to ~1e-7 rad where rho itself is quadratic."""
    theta = np.linspace(0.0, np.pi / 2, size)
    key = np.sqrt(diffuse_dolp(theta, n))
    if not np.all(np.diff(key) > 0):
        raise NormalsError(f"diffuse DoLP is not monotonic in the zenith for n = {n}: cannot invert")
    key.setflags(write=False)
    theta.setflags(write=False)
    return key, theta


def zenith_from_dolp(dolp: np.ndarray, n: float = DEFAULT_IOR, lut_size: int = LUT_SIZE) -> np.ndarray:
    """Zenith angle (radians, float32, [0, pi/2]) from diffuse DoLP, inverting ``diffuse_dolp`` by a vectorised
    lookup table. DoLP <= 0 or NaN gives 0; DoLP at or above ``diffuse_dolp(pi/2, n)`` gives pi/2."""
    key, theta = _zenith_lut(float(n), int(lut_size))
    d = np.nan_to_num(np.asarray(dolp, dtype=np.float64), nan=0.0, posinf=1.0, neginf=0.0)
    return np.interp(np.sqrt(np.clip(d, 0.0, None)), key, theta).astype(np.float32)


def azimuth_directions(aolp: np.ndarray, view: np.ndarray) -> np.ndarray:
    """(..., 3) unit vectors perpendicular to ``view`` whose image-plane projection lies along the AoLP: the
    normal's azimuth direction up to sign (diffuse polarization; see the module docstring)."""
    a = np.asarray(aolp, dtype=np.float64)
    v = np.asarray(view, dtype=np.float64)
    e = np.stack([np.cos(a), np.sin(a), np.zeros_like(a)], -1)
    t = -(e[..., 0] * v[..., 0] + e[..., 1] * v[..., 1]) / np.maximum(v[..., 2], 1e-6)
    p = e.copy()
    p[..., 2] = t
    return p / np.linalg.norm(p, axis=-1, keepdims=True)


def mask_centroid(mask: np.ndarray) -> tuple[float, float]:
    """(row, col) centroid of a boolean mask; the array centre when it is empty."""
    m = np.asarray(mask, dtype=bool)
    rows, cols = np.nonzero(m)
    if rows.size == 0:
        return (m.shape[0] - 1) / 2, (m.shape[1] - 1) / 2
    return float(rows.mean()), float(cols.mean())


def sfp_normals(dolp: np.ndarray, aolp: np.ndarray, view: np.ndarray | None = None, n: float = DEFAULT_IOR,
                mask: np.ndarray | None = None, resolve: str = "outward", center: tuple[float, float] | None = None,
                reference: np.ndarray | None = None) -> np.ndarray:
    """(H, W, 3) float32 unit normals in the camera frame from diffuse DoLP and AoLP (H, W).

    ``view``: (H, W, 3) viewing directions (``view_directions``); None: orthographic. ``n``: refractive index.
    ``resolve`` picks one of the two azimuth candidates (module docstring): "outward" (away from ``center`` =
    (row, col) in this array's pixels; default the centroid of ``mask``, or the array centre) or "reference"
    (closest to ``reference``, (H, W, 3)). Ties (candidate azimuth perpendicular to the rule's direction, or
    zenith 0) take the AoLP itself. Pixels outside ``mask`` (when given) are 0, the ground truth's "no surface"."""
    d = np.asarray(dolp)
    a = np.asarray(aolp)
    if d.ndim != 2 or a.shape != d.shape:
        raise NormalsError(f"sfp_normals: dolp {d.shape} and aolp {a.shape} must be equal (H, W) arrays")
    h, w = d.shape
    if view is None:
        view = view_directions((h, w))
    v = np.asarray(view, dtype=np.float64)
    if v.shape != (h, w, 3):
        raise NormalsError(f"sfp_normals: view {v.shape} must be (H, W, 3) = {(h, w, 3)}")
    m = None if mask is None else np.asarray(mask, dtype=bool)
    if m is not None and m.shape != (h, w):
        raise NormalsError(f"sfp_normals: mask {m.shape} must be (H, W) = {(h, w)}")
    theta = zenith_from_dolp(d, n).astype(np.float64)
    p = azimuth_directions(np.nan_to_num(a.astype(np.float64)), v)
    if resolve == "reference":
        if reference is None or np.shape(reference) != (h, w, 3):
            raise NormalsError(f"sfp_normals: resolve='reference' needs a (H, W, 3) reference, got "
                               f"{None if reference is None else np.shape(reference)}")
        score = np.einsum("hwc,hwc->hw", p, np.asarray(reference, dtype=np.float64))
    elif resolve == "outward":
        cy, cx = center if center is not None else mask_centroid(m) if m is not None else ((h - 1) / 2, (w - 1) / 2)
        rx = np.arange(w, dtype=np.float64)[None, :] - cx  # right
        ry = cy - np.arange(h, dtype=np.float64)[:, None]  # up
        score = p[..., 0] * rx + p[..., 1] * ry
    else:
        raise NormalsError(f"sfp_normals: resolve must be 'outward' or 'reference', got {resolve!r}")
    sign = np.where(score < 0, -1.0, 1.0)[..., None]
    normal = np.cos(theta)[..., None] * v + (np.sin(theta)[..., None] * sign) * p
    normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
    if m is not None:
        normal[~m] = 0
    return normal.astype(np.float32)


def angular_error_deg(pred: np.ndarray, gt: np.ndarray, mask: np.ndarray | None = None) -> np.ndarray:
    """Angle in degrees between ``pred`` and ``gt`` (..., 3) normals, float64, never NaN.

    Returns the per-pixel map (shape ``pred.shape[:-1]``) without ``mask``, else the 1-D errors of the pixels
    where ``mask`` is True (row-major order); mean and median are the caller's. Vectors need not be unit length
    (computed as atan2(|a x b|, a . b), accurate near 0 and 180 degrees); a zero (or non-finite) vector on either
    side counts as 90 degrees: no estimate, no credit, no NaN."""
    a = np.asarray(pred, dtype=np.float64)
    b = np.asarray(gt, dtype=np.float64)
    if a.shape != b.shape or a.shape[-1:] != (3,):
        raise NormalsError(f"angular_error_deg: pred {a.shape} and gt {b.shape} must be equal (..., 3) arrays")
    if mask is not None:
        m = np.asarray(mask, dtype=bool)
        if m.shape != a.shape[:-1]:
            raise NormalsError(f"angular_error_deg: mask {m.shape} must be {a.shape[:-1]}")
        a, b = a[m], b[m]
    bad = ~(np.isfinite(a).all(-1) & np.isfinite(b).all(-1))
    a = np.where(bad[..., None], 0.0, a)
    b = np.where(bad[..., None], 0.0, b)
    na, nb = np.linalg.norm(a, axis=-1), np.linalg.norm(b, axis=-1)
    zero = bad | (na < 1e-12) | (nb < 1e-12)
    err = np.degrees(np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), np.einsum("...c,...c->...", a, b)))
    return np.where(zero, 90.0, err)


def summarize_errors(err_deg: np.ndarray) -> dict[str, float]:
    """Mean, median, 90th percentile and the fractions within 11.25, 22.5 and 30 degrees (the usual normal
    estimation table) of 1-D per-pixel errors; NaN statistics (and n = 0) for no pixels."""
    e = np.asarray(err_deg, dtype=np.float64).ravel()
    if e.size == 0:
        nan = float("nan")
        return {"n_px": 0, "mean_deg": nan, "median_deg": nan, "p90_deg": nan, "within_11.25": nan,
                "within_22.5": nan, "within_30": nan}
    return {"n_px": int(e.size), "mean_deg": float(e.mean()), "median_deg": float(np.median(e)),
            "p90_deg": float(np.percentile(e, 90)), "within_11.25": float((e < 11.25).mean()),
            "within_22.5": float((e < 22.5).mean()), "within_30": float((e < 30).mean())}
