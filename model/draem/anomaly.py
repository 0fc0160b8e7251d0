"""DRAEM anomaly synthesis on polarimetric priors, channel-aware, batched in torch on the training device.

For each sample: a Perlin mask M (``perlin.perlin_masks``; optionally restricted to the object region), an
opacity beta ~ U(0, beta_max) (DRAEM: 0.8) and an anomaly source A; inside M the prior becomes
``(1 - beta) * A + beta * X``, outside it stays X. A fraction ``1 - anomaly_fraction`` of samples (DRAEM: half)
stays clean with an empty mask.

Anomaly sources. DRAEM blends textures from the DTD data set; DTD cannot be downloaded on this project's
machines, so the sources are (a) procedural textures (fractal Perlin noise with random gamma, inversion and
contrast range, mapped into each prior's value space) and (b) patches of other samples in the batch (flipped,
shifted, with a random brightness change for scalar priors or a random AoLP rotation). Which one is drawn per
sample with probability ``patch_fraction``.

Channel awareness (layout: ``config.channel_slices``; values in physical units before normalisation):
    intensity, dolp   scalars in [0, 1]: blended linearly, clipped to [0, 1]
    aolp              (cos 2*aolp, sin 2*aolp): blended as vectors and renormalised, i.e. on the circle with
                      AoLP's period pi; a zero-length blend falls back to the source direction
    normal            unit 3-vectors: blended and renormalised; procedural normals tilt up to 60 degrees from
                      the camera axis in a random azimuth

Normalisation: synthesis works on physical prior values; the caller normalises the clean and the augmented
batch with the same ``preprocess.Normalizer`` afterwards, so synthetic anomalies and real inputs share one scale
(the trap of anomalib PR 1431).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import torch

from .config import PRIOR_CHANNELS, SIGNED_PRIORS, UNIT_VECTOR_PRIORS, channel_slices, value_range
from .errors import ModelError
from .perlin import fractal_noise, perlin_masks
from .vectors import unit_vectors


@dataclass(frozen=True)
class AnomalyConfig:
    """DRAEM's synthesis parameters (defaults as published) plus ours: ``patch_fraction`` (other-sample patches
    vs procedural textures) and ``restrict_to_object`` (masks only where the object is)."""

    beta_max: float = 0.8
    anomaly_fraction: float = 0.5
    threshold: float = 0.5
    min_scale_exp: int = 0
    max_scale_exp: int = 5
    max_rotation_deg: float = 90.0
    patch_fraction: float = 0.5
    restrict_to_object: bool = True


@dataclass
class SyntheticBatch:
    """augmented: (B, C, H, W) priors with anomalies; mask: (B, H, W) float {0, 1}; label: (B,) float {0, 1}
    (1 iff the mask is non-empty)."""

    augmented: torch.Tensor
    mask: torch.Tensor
    label: torch.Tensor


def _uniform(b: int, lo: float, hi: float, g: torch.Generator) -> torch.Tensor:
    return lo + (hi - lo) * torch.rand(b, generator=g, device=g.device)


def _normalise(v: torch.Tensor, fallback: torch.Tensor) -> torch.Tensor:
    return unit_vectors(v, 1, fallback=fallback)


def _texture_scalar(b: int, h: int, w: int, g: torch.Generator) -> torch.Tensor:
    t = fractal_noise(b, h, w, g)
    gamma = torch.exp(_uniform(b, math.log(0.5), math.log(2.0), g)).view(b, 1, 1)
    t = t.pow(gamma)
    invert = (torch.rand(b, generator=g, device=g.device) < 0.5).view(b, 1, 1)
    t = torch.where(invert, 1 - t, t)
    lo, hi = _uniform(b, 0.0, 1.0, g), _uniform(b, 0.0, 1.0, g)
    lo, hi = torch.minimum(lo, hi).view(b, 1, 1), torch.maximum(lo, hi).view(b, 1, 1)
    return (lo + (hi - lo) * t).unsqueeze(1)


def _texture_aolp(b: int, h: int, w: int, g: torch.Generator) -> torch.Tensor:
    t = fractal_noise(b, h, w, g)
    psi = (_uniform(b, 0, 2 * math.pi, g).view(b, 1, 1) + _uniform(b, 0.25, 2.0, g).view(b, 1, 1) * 2 * math.pi * t)
    return torch.stack((torch.cos(psi), torch.sin(psi)), dim=1)  # psi = 2 * aolp


def _texture_normal(b: int, h: int, w: int, g: torch.Generator) -> torch.Tensor:
    tilt = fractal_noise(b, h, w, g) * torch.deg2rad(_uniform(b, 10.0, 60.0, g)).view(b, 1, 1)
    azimuth = fractal_noise(b, h, w, g) * 2 * math.pi + _uniform(b, 0, 2 * math.pi, g).view(b, 1, 1)
    s = torch.sin(tilt)
    return torch.stack((s * torch.cos(azimuth), s * torch.sin(azimuth), torch.cos(tilt)), dim=1)


def _patches(x: torch.Tensor, priors: tuple[str, ...], g: torch.Generator) -> torch.Tensor:
    """Other samples of the batch, flipped and shifted, with a random brightness change or AoLP rotation."""
    b, _, h, w = x.shape
    k = int(torch.randint(1, b, (1,), generator=g, device=g.device).item())
    src = x.roll(k, dims=0)
    flip_v = (torch.rand(b, generator=g, device=g.device) < 0.5).view(b, 1, 1, 1)
    flip_h = (torch.rand(b, generator=g, device=g.device) < 0.5).view(b, 1, 1, 1)
    src = torch.where(flip_v, src.flip(2), src)
    src = torch.where(flip_h, src.flip(3), src)
    dy, dx = (int(v) for v in torch.randint(0, max(h, w), (2,), generator=g, device=g.device))
    src = src.roll((dy % h, dx % w), dims=(2, 3))
    # flipping mirrors a vector field's geometry: AoLP and normal directions change with it; as anomaly sources
    # that is harmless (they only need to be plausible-looking but wrong), so no correction is applied
    out = src.clone()
    for p, sl in channel_slices(priors).items():
        if p == "aolp":
            rot = _uniform(b, 0, 2 * math.pi, g).view(b, 1, 1)
            c, s = src[:, sl.start], src[:, sl.start + 1]
            out[:, sl.start], out[:, sl.start + 1] = torch.cos(rot) * c - torch.sin(rot) * s, \
                torch.sin(rot) * c + torch.cos(rot) * s
        elif p not in UNIT_VECTOR_PRIORS:
            gain = _uniform(b, 0.5, 1.5, g).view(b, 1, 1, 1)
            out[:, sl] = (src[:, sl] * gain + _uniform(b, -0.2, 0.2, g).view(b, 1, 1, 1)).clamp(*value_range(p))
    return out


def anomaly_sources(x: torch.Tensor, priors: tuple[str, ...], generator: torch.Generator,
                    patch_fraction: float = 0.5) -> torch.Tensor:
    """(B, C, H, W) anomaly sources in each prior's value space: procedural textures or other samples' patches."""
    b, _, h, w = x.shape
    tex = []
    for p in priors:
        tex.append(_texture_aolp(b, h, w, generator) if p == "aolp" else
                   _texture_normal(b, h, w, generator) if p == "normal" else
                   _texture_scalar(b, h, w, generator) * 2 - 1 if p in SIGNED_PRIORS else
                   _texture_scalar(b, h, w, generator))
    texture = torch.cat(tex, dim=1).to(x.dtype)
    if b < 2 or patch_fraction <= 0:
        return texture
    use_patch = (torch.rand(b, generator=generator, device=generator.device) < patch_fraction).view(b, 1, 1, 1)
    return torch.where(use_patch, _patches(x, priors, generator), texture)


def synthesize(x: torch.Tensor, priors: tuple[str, ...], generator: torch.Generator,
               config: AnomalyConfig = AnomalyConfig(), object_mask: torch.Tensor | None = None) -> SyntheticBatch:
    """DRAEM-style synthetic anomalies on a batch of stacked priors.

    Parameters
    ----------
    x : (B, C, H, W) float priors in physical units, channels as ``config.channel_slices(priors)``.
    priors : prior names, in channel order.
    generator : all randomness; must be on ``x.device``.
    object_mask : (B, H, W) bool, where the object is; masks are cut to it when ``config.restrict_to_object``.
    """
    b, c, h, w = x.shape
    if c != sum(PRIOR_CHANNELS[p] for p in priors):
        raise ModelError(f"synthesize: {c} channels do not match priors {priors}")
    if generator.device != x.device:
        raise ModelError(f"synthesize: generator on {generator.device}, batch on {x.device}")
    g = generator
    mask = perlin_masks(b, h, w, g, config.threshold, config.min_scale_exp, config.max_scale_exp,
                        config.max_rotation_deg)
    if config.restrict_to_object and object_mask is not None:
        mask &= object_mask.bool()
    anomalous = torch.rand(b, generator=g, device=g.device) < config.anomaly_fraction
    mask &= anomalous.view(b, 1, 1)
    beta = (torch.rand(b, generator=g, device=g.device) * config.beta_max).view(b, 1, 1, 1).to(x.dtype)
    source = anomaly_sources(x, priors, g, config.patch_fraction)
    m = mask.unsqueeze(1).to(x.dtype)
    out = torch.empty_like(x)
    for p, sl in channel_slices(priors).items():
        xs, src = x[:, sl], source[:, sl]
        blend = (1 - beta) * src + beta * xs
        blend = _normalise(blend, src) if p in UNIT_VECTOR_PRIORS else blend.clamp(*value_range(p))
        out[:, sl] = xs * (1 - m) + blend * m
    maskf = mask.to(x.dtype)
    return SyntheticBatch(out, maskf, (maskf.flatten(1).amax(1) > 0).to(x.dtype))
