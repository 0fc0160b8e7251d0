"""Which input channels carry a signal the reconstructive network can learn.

Per channel of the stacked priors, on good parts' object pixels: the variance of the normalised input, the share of
it the reconstruction leaves unexplained (mean squared residual / variance: 0 = reproduced, about 1 = not at all),
and the correlation of horizontally adjacent pixels (near 1 for a smooth image, near 0 for pixel noise). A channel
that is mostly pixel noise cannot be reconstructed, so its residual is noise the discriminative network must learn
to ignore: a diagnosis of why a prior adds little (docs/model.md, the ablation on a fixed station).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import torch

from model.draem.detector import Detector
from model.draem.errors import ModelError

CHANNEL_NAMES = {"intensity": ("intensity",), "dolp": ("dolp",), "aolp": ("aolp_cos", "aolp_sin"),
                 "normal": ("normal_x", "normal_y", "normal_z"), "tilt_x": ("tilt_x",), "tilt_y": ("tilt_y",)}
"""Names of each prior's channels, in stacking order (``model.draem.preprocess.stack_priors``)."""


@dataclass(frozen=True)
class ChannelStats:
    """One input channel on object pixels of good parts; None where undefined (a constant channel)."""

    channel: str
    variance: float
    unexplained: float | None
    adjacent_corr: float | None


def channel_names(priors: Sequence[str]) -> list[str]:
    return [c for p in priors for c in CHANNEL_NAMES[p]]


def adjacent_correlation(img: torch.Tensor, mask: torch.Tensor) -> float | None:
    """Pearson correlation of horizontally adjacent pixels of (N, H, W) ``img`` where both lie in ``mask``."""
    both = mask[..., :-1] & mask[..., 1:]
    a, b = img[..., :-1][both].double(), img[..., 1:][both].double()
    if a.numel() < 2:
        return None
    a, b = a - a.mean(), b - b.mean()
    den = float((a.square().sum() * b.square().sum()).sqrt())
    return float((a * b).sum()) / den if den > 0 else None


@torch.no_grad()
def channel_stats(detector: Detector, x: torch.Tensor, object_mask: torch.Tensor, batch_size: int = 16
                  ) -> list[ChannelStats]:
    """Stats of each channel of (N, C, S, S) physical priors ``x`` (good parts) over ``object_mask`` (N, S, S)."""
    if detector.training:
        raise ModelError("channel_stats needs eval mode: call detector.eval()")
    mask = object_mask.bool()
    if not bool(mask.any()):
        raise ModelError("channel_stats: no object pixels")
    z = detector.normalize(x.float())
    rec = torch.empty_like(z)
    for name, member in detector.members.items():
        sl = detector.member_slice(name)
        for i in range(0, len(z), batch_size):
            rec[i:i + batch_size, sl] = member.reconstructive(z[i:i + batch_size, sl]).float()
    out = []
    for c, name in enumerate(channel_names(detector.config.priors)):
        v = z[:, c][mask].double()
        var = float(v.var()) if v.numel() > 1 else 0.0
        mse = float((rec[:, c] - z[:, c])[mask].double().square().mean())
        out.append(ChannelStats(name, var, mse / var if var > 0 else None, adjacent_correlation(z[:, c], mask)))
    return out
