"""From prior maps to network input: stacking channels, cropping the part, resizing, normalising.

The same functions run at training and at inspection time so the network always sees the same kind of input.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import torch
import torch.nn.functional as F

from .config import PRIOR_CHANNELS, UNIT_VECTOR_PRIORS, channel_slices
from .errors import ModelError
from .vectors import unit_vectors


def stack_priors(maps: Mapping[str, np.ndarray], priors: tuple[str, ...]) -> np.ndarray:
    """(C, H, W) float32 network channels from prior maps.

    ``maps`` holds (H, W) float arrays "intensity", "dolp", "aolp_cos" and "aolp_sin" (as returned by
    ``model.priors.compute_priors``; or "aolp" in radians, converted to (cos 2a, sin 2a)) and "normal" (H, W, 3),
    unit camera-frame normals. Conventions: ``model.priors.conventions``."""
    out = []
    for p in priors:
        try:
            if p == "aolp":
                if "aolp_cos" in maps:
                    out += [maps["aolp_cos"], maps["aolp_sin"]]
                else:
                    a2 = 2.0 * np.asarray(maps["aolp"], dtype=np.float32)
                    out += [np.cos(a2), np.sin(a2)]
            elif p == "normal":
                n = np.asarray(maps["normal"], dtype=np.float32)
                if n.ndim != 3 or n.shape[-1] != 3:
                    raise ModelError(f"normal map must be (H, W, 3), got {n.shape}")
                out += [n[..., 0], n[..., 1], n[..., 2]]
            else:
                out.append(maps[p])
        except KeyError as exc:
            raise ModelError(f"prior maps lack {exc.args[0]!r} needed for prior {p!r}; have {sorted(maps)}") from None
    shapes = {np.shape(a) for a in out}
    if len(shapes) != 1:
        raise ModelError(f"prior maps differ in shape: {sorted(shapes)}")
    return np.stack([np.asarray(a, dtype=np.float32) for a in out])


def crop_resize(x: np.ndarray | torch.Tensor, box: tuple[int, int, int, int], size_px: int | tuple[int, int],
                priors: tuple[str, ...], masks: tuple[np.ndarray, ...] = ()
                ) -> tuple[torch.Tensor, tuple[torch.Tensor, ...]]:
    """Crop (C, H, W) stacked priors to ``box`` and resize to (C, *size) (``size_px``: (height, width), or one int
    for a square; bilinear, antialiased when shrinking; unit-vector priors renormalised). ``masks``: (H, W) bool
    maps cropped and resized alike (area, then >= 0.5)."""
    t = torch.as_tensor(x, dtype=torch.float32)
    top, left, hh, ww = box
    size = (size_px, size_px) if isinstance(size_px, int) else tuple(size_px)
    t = t[:, top:top + hh, left:left + ww].unsqueeze(0)
    t = F.interpolate(t, size=size, mode="bilinear", align_corners=False,
                      antialias=hh > size[0] or ww > size[1])[0]
    for p, sl in channel_slices(priors).items():
        if p in UNIT_VECTOR_PRIORS:
            t[sl] = unit_vectors(t[sl], 0, fallback=t[sl])
    out_masks = []
    for m in masks:
        mt = torch.as_tensor(np.asarray(m, dtype=np.float32))[top:top + hh, left:left + ww][None, None]
        out_masks.append(F.interpolate(mt, size=size, mode="area")[0, 0] >= 0.5)
    return t, tuple(out_masks)


def crop_around(x: np.ndarray | torch.Tensor, box: tuple[int, int, int, int], size_px: tuple[int, int],
                priors: tuple[str, ...]) -> torch.Tensor:
    """``crop_resize`` of (C, H, W) stacked priors to a ``box`` that may reach outside them
    (``model.draem.roi.around_box``): NaN there, and in every output pixel that reads it."""
    t = torch.as_tensor(x, dtype=torch.float32)
    top, left, hh, ww = box
    pad = (max(-left, 0), max(left + ww - t.shape[2], 0), max(-top, 0), max(top + hh - t.shape[1], 0))
    if any(pad):
        t = F.pad(t, pad, value=float("nan"))
    return crop_resize(t, (top + pad[2], left + pad[0], hh, ww), size_px, priors)[0]


@dataclass(frozen=True)
class Normalizer:
    """Per-channel affine normalisation ``(x - mean) / std``; stats from training data on object pixels.

    Applied to clean and synthetic-anomaly inputs alike (after synthesis), and at inspection time."""

    mean: tuple[float, ...]
    std: tuple[float, ...]

    @classmethod
    def fit(cls, x: torch.Tensor, object_mask: torch.Tensor | None = None) -> Normalizer:
        """Stats of (N, C, H, W) ``x`` over pixels where ``object_mask`` (N, H, W) is True (all pixels if None)."""
        c = x.shape[1]
        flat = x.transpose(0, 1).reshape(c, -1).double()
        if object_mask is not None and object_mask.any():
            flat = flat[:, object_mask.reshape(-1).bool()]
        mean = flat.mean(1)
        std = flat.std(1).clamp_min(1e-3)
        return cls(tuple(float(v) for v in mean), tuple(float(v) for v in std))

    @classmethod
    def identity(cls, channels: int) -> Normalizer:
        return cls((0.0,) * channels, (1.0,) * channels)

    def __call__(self, x: torch.Tensor) -> torch.Tensor:
        if x.shape[-3] != len(self.mean):
            raise ModelError(f"normalizer has {len(self.mean)} channels, input has {x.shape[-3]}")
        shape = (-1, 1, 1)
        mean = torch.tensor(self.mean, dtype=x.dtype, device=x.device).view(shape)
        std = torch.tensor(self.std, dtype=x.dtype, device=x.device).view(shape)
        return (x - mean) / std

    def select(self, sl: slice) -> Normalizer:
        return Normalizer(self.mean[sl], self.std[sl])


def channels_of(priors: tuple[str, ...]) -> int:
    return sum(PRIOR_CHANNELS[p] for p in priors)
