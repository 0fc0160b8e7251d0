"""Perlin noise and DRAEM's Perlin anomaly masks, vectorised over a batch in torch, on any device.

DRAEM's masks (official code): per sample, lattice scales 2**U{0..5} drawn independently per axis, noise rotated by
U(-90, 90) degrees, thresholded at 0.5. Here the rotation is applied to the sampling coordinates rather than to a
rendered image, so rotated masks have no empty corners and any height/width works (no divisibility constraint).
All randomness comes from an explicit ``torch.Generator`` that lives on the output device.
"""

from __future__ import annotations

import math

import torch


def _fade(t: torch.Tensor) -> torch.Tensor:
    return t * t * t * (t * (t * 6 - 15) + 10)


def perlin_noise(res_y: torch.Tensor, res_x: torch.Tensor, height: int, width: int,
                 generator: torch.Generator, angle_rad: torch.Tensor | None = None) -> torch.Tensor:
    """Gradient (Perlin) noise, one field per sample.

    Parameters
    ----------
    res_y, res_x : (B,) float tensors, lattice cells across the image height / width (the noise's scale).
    height, width : output size in pixels (any positive integers).
    generator : source of the random gradients; its device is the output device.
    angle_rad : (B,) rotation of the sampling grid about the image centre (counter-clockwise), or None.

    Returns
    -------
    (B, height, width) float32, roughly in [-1, 1] (sqrt(2) times the classic 2D Perlin range, as DRAEM).
    """
    device = generator.device
    b = res_y.shape[0]
    ys = torch.arange(height, device=device, dtype=torch.float32) + 0.5 - height / 2
    xs = torch.arange(width, device=device, dtype=torch.float32) + 0.5 - width / 2
    yy, xx = torch.meshgrid(ys, xs, indexing="ij")
    yy, xx = yy.expand(b, -1, -1), xx.expand(b, -1, -1)
    if angle_rad is not None:
        c, s = torch.cos(angle_rad).view(b, 1, 1), torch.sin(angle_rad).view(b, 1, 1)
        yy, xx = c * yy - s * xx, s * yy + c * xx
    gy = yy * (res_y.view(b, 1, 1).float() / height)
    gx = xx * (res_x.view(b, 1, 1).float() / width)
    gy = gy - gy.amin(dim=(1, 2), keepdim=True).floor()  # lattice coordinates >= 0 per sample
    gx = gx - gx.amin(dim=(1, 2), keepdim=True).floor()
    ny = int(gy.max().floor().item()) + 2  # lattice points per axis covering every sample
    nx = int(gx.max().floor().item()) + 2
    angles = torch.rand((b, ny * nx), generator=generator, device=device) * (2 * math.pi)
    grad_y, grad_x = torch.cos(angles), torch.sin(angles)  # (B, ny*nx) unit gradients
    iy, ix = gy.floor(), gx.floor()
    fy, fx = gy - iy, gx - ix
    iy, ix = iy.long().view(b, -1), ix.long().view(b, -1)
    fy, fx = fy.view(b, -1), fx.view(b, -1)

    def corner(dy: int, dx: int) -> torch.Tensor:
        idx = (iy + dy) * nx + (ix + dx)
        return torch.gather(grad_y, 1, idx) * (fy - dy) + torch.gather(grad_x, 1, idx) * (fx - dx)

    ty, tx = _fade(fy), _fade(fx)
    n0 = torch.lerp(corner(0, 0), corner(0, 1), tx)
    n1 = torch.lerp(corner(1, 0), corner(1, 1), tx)
    return (math.sqrt(2) * torch.lerp(n0, n1, ty)).view(b, height, width)


def random_scales(batch: int, generator: torch.Generator, min_exp: int = 0, max_exp: int = 5) -> torch.Tensor:
    """(B,) float: 2**U{min_exp..max_exp} (inclusive), DRAEM's per-axis Perlin scale."""
    e = torch.randint(min_exp, max_exp + 1, (batch,), generator=generator, device=generator.device)
    return torch.pow(2.0, e.float())


def perlin_masks(batch: int, height: int, width: int, generator: torch.Generator, threshold: float = 0.5,
                 min_scale_exp: int = 0, max_scale_exp: int = 5, max_rotation_deg: float = 90.0) -> torch.Tensor:
    """DRAEM's anomaly masks: (B, height, width) bool, True where the rotated Perlin noise exceeds ``threshold``.

    Scales 2**U{min..max} per axis (DRAEM: 0..5), rotation U(-max_rotation_deg, +max_rotation_deg)."""
    res_y = random_scales(batch, generator, min_scale_exp, max_scale_exp)
    res_x = random_scales(batch, generator, min_scale_exp, max_scale_exp)
    angle = (torch.rand(batch, generator=generator, device=generator.device) * 2 - 1) * math.radians(max_rotation_deg)
    return perlin_noise(res_y, res_x, height, width, generator, angle) > threshold


def fractal_noise(batch: int, height: int, width: int, generator: torch.Generator, octaves: int = 4,
                  persistence: float = 0.5, min_scale_exp: int = 0, max_scale_exp: int = 4) -> torch.Tensor:
    """(B, height, width) fractal Perlin noise (``octaves`` doubling frequencies), rescaled to [0, 1] per sample:
    a procedural texture for anomaly sources."""
    res = random_scales(batch, generator, min_scale_exp, max_scale_exp)
    angle = torch.rand(batch, generator=generator, device=generator.device) * (2 * math.pi)
    out = torch.zeros((batch, height, width), device=generator.device)
    amp = 1.0
    for _ in range(octaves):
        out += amp * perlin_noise(res, res, height, width, generator, angle)
        res, amp = res * 2, amp * persistence
    lo = out.amin(dim=(1, 2), keepdim=True)
    hi = out.amax(dim=(1, 2), keepdim=True)
    return (out - lo) / (hi - lo).clamp_min(1e-6)
