"""Known Stokes scenes for tests and benchmarks of demosaicking (numpy only).

``detailed_stokes`` draws a scene with what separates demosaicking methods: sharp (anti-aliased) edges between
regions of different intensity and polarization, smooth gradients, fine gratings near the sampling limit, noise
texture, thin lines, and DoLP/AoLP that vary both smoothly and abruptly. Units and conventions:
``conventions.py`` (full scale; S0 in [0, 2]; AoLP counter-clockwise from image right).
"""

from __future__ import annotations

import numpy as np

S0_RANGE = (0.04, 1.2)
"""S0 stays in this range and DoLP <= MAX_DOLP, so every polarizer intensity ``0.5 * S0 * (1 + DoLP)`` is
below 0.96: the scene never saturates a sensor at full scale."""
MAX_DOLP = 0.6


def _coverage(signed_distance_px: np.ndarray) -> np.ndarray:
    """Area fraction of a pixel inside a shape from its signed distance (px, positive inside): a 1-px ramp, as a
    sharp edge seen through a lens, without the aliasing of a binary mask."""
    return np.clip(signed_distance_px + 0.5, 0.0, 1.0)


def _blur121(a: np.ndarray) -> np.ndarray:
    """Separable [1, 2, 1] / 4 smoothing with edge padding (keeps noise texture fine but not white)."""
    p = np.pad(a, 1, mode="edge")
    a = (p[:-2, 1:-1] + 2 * p[1:-1, 1:-1] + p[2:, 1:-1]) / 4
    p = np.pad(a, ((0, 0), (1, 1)), mode="edge")
    return (p[:, :-2] + 2 * p[:, 1:-1] + p[:, 2:]) / 4


def detailed_stokes(height: int, width: int, seed: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A (height, width) scene of known linear Stokes images (S0, S1, S2), float32, full-scale units.

    Content (sizes relative to the image, so any size from ~32 px up has all of it): gradients of S0, DoLP and
    AoLP over the whole image; discs and rotated rectangles with their own S0, DoLP and AoLP (edges in
    intensity only, in polarization only, and in both); a sphere-like disc with AoLP = azimuth and DoLP rising
    to the rim, as diffuse reflection gives; gratings with periods of 2.5 to 8 px; noise texture; one-pixel
    lines. Deterministic for a given ``seed``. DoLP <= MAX_DOLP and S0 within S0_RANGE (no saturation).
    """
    if height < 8 or width < 8:
        raise ValueError(f"detailed_stokes needs at least 8x8 pixels, got {height}x{width}")
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:height, 0:width].astype(np.float64)
    size = float(min(height, width))
    u, v = x / width, y / height

    # Smooth background: gradients of all three quantities.
    s0 = 0.3 + 0.6 * u * (1.0 - 0.4 * v)
    dol = 0.05 + 0.4 * v
    aol = np.pi * (0.8 * u + 0.4 * v)

    def paint(mask: np.ndarray, s0_value, dolp_value, aolp_value,
              box: tuple[slice, slice] = (slice(None), slice(None))) -> None:
        """Blend values into the scene with coverage ``mask`` over the window ``box``."""
        if s0_value is not None:
            s0[box] += mask * (s0_value - s0[box])
        if dolp_value is not None:
            dol[box] += mask * (dolp_value - dol[box])
        if aolp_value is not None:  # blend on the circle of period pi, so an edge has no spurious angle
            z = (1 - mask) * np.exp(2j * aol[box]) + mask * np.exp(2j * np.asarray(aolp_value))
            aol[box] = 0.5 * np.angle(z)

    n_shapes = 6 + int(height * width / 96**2) // 4
    for k in range(n_shapes):
        cy, cx = rng.uniform(0, height), rng.uniform(0, width)
        r = size * rng.uniform(0.04, 0.18)
        kind = k % 3  # what the edge is made of: 0 intensity and polarization, 1 intensity only, 2 polarization only
        s0_v = rng.uniform(0.1, 1.1) if kind != 2 else None
        d_v = rng.uniform(0.0, MAX_DOLP) if kind != 1 else None
        a_v = rng.uniform(0, np.pi) if kind != 1 else None
        m = int(r) + 2  # shapes are painted inside their bounding box only: full frames stay fast
        box = (slice(max(int(cy) - m, 0), int(cy) + m), slice(max(int(cx) - m, 0), int(cx) + m))
        yy, xx = y[box] - cy, x[box] - cx
        if rng.random() < 0.5:
            mask = _coverage(r - np.hypot(yy, xx))
        else:
            t = rng.uniform(0, np.pi)
            along = xx * np.cos(t) + yy * np.sin(t)
            across = -xx * np.sin(t) + yy * np.cos(t)
            mask = _coverage(np.minimum(r - np.abs(along), 0.5 * r - np.abs(across)))
        paint(mask, s0_v, d_v, a_v, box)

    # Sphere-like disc: AoLP = azimuth (radial), DoLP grows toward the rim, shading in S0.
    cy, cx, r = 0.7 * height, 0.3 * width, 0.2 * size
    m = int(r) + 2
    box = (slice(max(int(cy) - m, 0), int(cy) + m), slice(max(int(cx) - m, 0), int(cx) + m))
    yy, xx = y[box] - cy, x[box] - cx
    rho = np.hypot(yy, xx) / r
    paint(_coverage(r * (1 - rho)), 0.25 + 0.8 * np.sqrt(np.clip(1 - rho**2, 0, 1)),
          MAX_DOLP * np.clip(rho, 0, 1) ** 2, np.arctan2(-yy, xx), box)

    # Gratings near the sampling limit (periods 2.5-8 px) in a band, in intensity and in AoLP.
    band = _coverage(np.minimum(y - 0.42 * height, 0.58 * height - y))
    period = 2.5 + 5.5 * u
    theta = 0.3
    phase = 2 * np.pi * (x * np.cos(theta) + y * np.sin(theta)) / period
    s0 = s0 * (1 + 0.35 * band * np.sin(phase))
    aol = aol + 0.5 * band * np.sin(phase + 1.0)

    # Noise texture (fine but not white) in the right third, in intensity and DoLP.
    tex = _coverage(x - 0.66 * width)
    s0 = s0 * (1 + 0.25 * tex * _blur121(rng.standard_normal((height, width))))
    dol = dol * (1 + 0.3 * tex * _blur121(rng.standard_normal((height, width))))

    # One-pixel lines: a dark scratch and a polarized bright line.
    for frac, s0_v, d_v in ((0.15, 0.08, None), (0.85, 1.1, 0.5)):
        t = 0.2 + frac
        dist = (x - frac * width) * np.cos(t) - (y - 0.5 * height) * np.sin(t)
        paint(_coverage(0.5 - np.abs(dist)), s0_v, d_v, None)

    s0 = np.clip(s0, *S0_RANGE)
    dol = np.clip(dol, 0.0, MAX_DOLP)
    s1 = s0 * dol * np.cos(2 * aol)
    s2 = s0 * dol * np.sin(2 * aol)
    return s0.astype(np.float32), s1.astype(np.float32), s2.astype(np.float32)
