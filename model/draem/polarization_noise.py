"""Polarization noise as a training augmentation: the same part seen with noisier Stokes components.

DoLP is the length of the normalised Stokes vector (S1, S2) / S0, and the length of a noisy vector is biased up:
E|s + n| = sqrt(|s|^2 + 2 sigma^2) roughly. So every source of noise in S1 and S2 (photon and read noise at a
short exposure or high gain, a renderer's Monte Carlo noise) raises the DoLP of a weakly polarizing part. Measured
on the shipped line (band input, good parts' median DoLP): 0.095 at 16 spp, 0.141 at 8 spp, and networks trained
at 16 spp scored every 8-spp good part as a defect (8 robust SD above their good validation parts; this module's
noise at sigma 0.08 reproduces that: 7.7 SD). A station cannot know its line's noise level in advance, so the
networks should learn that it is not a defect. Measured: a 600-step fine-tune of the shipped networks at sigma 0.1
halved the 8-spp shift relative to the gap between good and defective parts, but not in robust SD (7.9): the DoLP
bias is one cause among others, and the option is off by default (docs/results/2026-11-24-low-rank-variation.md).

Convention: ``x`` (N, C, H, W) physical priors stacked as ``config.channel_slices(priors)``; the model must read
DoLP (AoLP alone has no length to bias). Per sample, sigma ~ U(0, ``sigma_max``) in units of S0; the noise is
drawn on a grid twice as fine as the input and averaged back (DoLP as the mean of the fine lengths, AoLP as the
direction of the mean fine vector), as the priors are computed at the frame's resolution and then shrunk to the
input: the bias comes through, the pixel-level texture at half amplitude. Intensity and normals are left as they
are. Pure and seeded by ``generator``; finite for finite input.
"""

from __future__ import annotations

import torch
import torch.nn.functional as F

from .config import channel_slices


def add_polarization_noise(x: torch.Tensor, priors: tuple[str, ...], sigma_max: float,
                           generator: torch.Generator) -> torch.Tensor:
    """``x`` with Stokes noise of a random level per sample (module docstring); ``x`` itself when ``sigma_max`` is 0
    or the model does not read DoLP."""
    sl = channel_slices(priors)
    if sigma_max <= 0 or "dolp" not in sl:
        return x
    n = x.shape[0]
    d = sl["dolp"].start
    dolp = x[:, d].clamp(0.0, 1.0)
    if "aolp" in sl:
        a = sl["aolp"].start
        direction = x[:, a:a + 2]
    else:  # the angle is unknown: any direction gives the same length
        direction = torch.stack([torch.ones_like(dolp), torch.zeros_like(dolp)], 1)
    s = (dolp.unsqueeze(1) * direction).float()
    sigma = torch.rand(n, generator=generator, device=generator.device).to(x.device) * sigma_max
    fine = F.interpolate(s, scale_factor=2, mode="nearest")
    noise = torch.randn(fine.shape, generator=generator, device=generator.device).to(x.device)
    fine = fine + sigma.view(n, 1, 1, 1) * noise
    length = F.avg_pool2d(fine.norm(dim=1, keepdim=True), 2)[:, 0]
    mean = F.avg_pool2d(fine, 2)
    out = x.clone()
    out[:, d] = length.clamp(0.0, 1.0).to(x.dtype)
    if "aolp" in sl:
        norm = mean.norm(dim=1, keepdim=True)
        out[:, a:a + 2] = torch.where(norm > 1e-6, mean / norm.clamp_min(1e-6), direction.float()).to(x.dtype)
    return out
