"""DRAEM's loss: L = L2(X, X_r) + L_SSIM(X, X_r) + L_focal(M, M_hat), each with weight 1 (as the official code).

    L2      mean squared error between the clean prior X and the reconstruction X_r (normalised units)
    L_SSIM  1 - mean SSIM (11x11 Gaussian window, sigma 1.5, per channel), dynamic range L = 1 as DRAEM
            (the official code picks L from the image's range; our inputs are normalised, so L is fixed)
    focal   focal loss, gamma 2, no class weighting, on the softmax of the 2-class logits vs the mask

Ours (mixed supervision): an optional per-pixel weight of the two reconstruction terms (``draem_loss``'s
``recon_weight``), 0 where a rendered defect has no clean counterpart to reconstruct.
"""

from __future__ import annotations

from dataclasses import dataclass

import torch
import torch.nn.functional as F

W_L2 = 1.0
W_SSIM = 1.0
W_FOCAL = 1.0


def _gaussian_window(size: int, sigma: float, channels: int, device: torch.device, dtype: torch.dtype
                     ) -> torch.Tensor:
    x = torch.arange(size, device=device, dtype=torch.float32) - size // 2
    g = torch.exp(-(x**2) / (2 * sigma**2))
    g = g / g.sum()
    return (g[:, None] * g[None, :]).expand(channels, 1, size, size).to(dtype).contiguous()


def ssim_map(a: torch.Tensor, b: torch.Tensor, window_size: int = 11, data_range: float = 1.0) -> torch.Tensor:
    """(N, C, H, W) local SSIM of ``a`` and ``b`` (Gaussian window, sigma 1.5, zero padding as DRAEM)."""
    c = a.shape[1]
    win = _gaussian_window(window_size, 1.5, c, a.device, a.dtype)
    pad = window_size // 2
    mu_a = F.conv2d(a, win, padding=pad, groups=c)
    mu_b = F.conv2d(b, win, padding=pad, groups=c)
    var_a = F.conv2d(a * a, win, padding=pad, groups=c) - mu_a**2
    var_b = F.conv2d(b * b, win, padding=pad, groups=c) - mu_b**2
    cov = F.conv2d(a * b, win, padding=pad, groups=c) - mu_a * mu_b
    c1, c2 = (0.01 * data_range) ** 2, (0.03 * data_range) ** 2
    return ((2 * mu_a * mu_b + c1) * (2 * cov + c2)) / ((mu_a**2 + mu_b**2 + c1) * (var_a + var_b + c2))


def focal_loss(logits: torch.Tensor, mask: torch.Tensor, gamma: float = 2.0) -> torch.Tensor:
    """Mean focal loss ``-(1 - p_t)**gamma * log p_t``; logits (N, 2, H, W), mask (N, H, W) in {0, 1}."""
    logp = F.log_softmax(logits.float(), dim=1)
    logp_t = torch.where(mask.bool(), logp[:, 1], logp[:, 0])
    return (-(1 - logp_t.exp()) ** gamma * logp_t).mean()


@dataclass
class LossTerms:
    total: torch.Tensor
    l2: torch.Tensor
    ssim: torch.Tensor
    focal: torch.Tensor

    def as_floats(self) -> dict[str, float]:
        return {k: float(getattr(self, k).detach()) for k in ("total", "l2", "ssim", "focal")}


def ssim_window_weight(weight: torch.Tensor, window_size: int = 11) -> torch.Tensor:
    """(N, H, W) weight for the SSIM term: the minimum of ``weight`` over each pixel's ``window_size`` square, so a
    pixel with weight 0 enters no SSIM window that counts (its value then changes neither loss term)."""
    pad = window_size // 2
    return -F.max_pool2d(-weight.float().unsqueeze(1), window_size, stride=1, padding=pad).squeeze(1)


def draem_loss(clean: torch.Tensor, reconstruction: torch.Tensor, logits: torch.Tensor, mask: torch.Tensor,
               recon_weight: torch.Tensor | None = None) -> LossTerms:
    """``W_L2 * L2 + W_SSIM * (1 - SSIM) + W_FOCAL * focal`` (all weights 1, as published).

    clean, reconstruction: (N, C, H, W); logits: (N, 2, H, W); mask: (N, H, W) in {0, 1}, the discriminative target.
    ``recon_weight``: optional (N, H, W) per-pixel weight in [0, 1] of the reconstruction terms (mixed supervision:
    0 on a rendered defect whose clean render is unknown). None is the published loss, computed exactly as before.
    With a weight, L2 is the weighted mean of the squared error over pixels and channels, and 1 - SSIM uses the
    weighted mean of the SSIM map with the weight's minimum over each 11x11 SSIM window (``ssim_window_weight``):
    a weight-0 pixel influences neither term. The focal term is never weighted."""
    rec = reconstruction.float()
    focal = focal_loss(logits, mask)
    if recon_weight is None:
        l2 = F.mse_loss(rec, clean.float())
        ssim = 1 - ssim_map(rec, clean.float()).mean()
    else:
        c = rec.shape[1]
        w = recon_weight.float().unsqueeze(1)
        ws = ssim_window_weight(recon_weight).unsqueeze(1)
        l2 = (w * (rec - clean.float()) ** 2).sum() / (w.sum() * c).clamp_min(1e-12)
        ssim = 1 - (ws * ssim_map(rec, clean.float())).sum() / (ws.sum() * c).clamp_min(1e-12)
    return LossTerms(W_L2 * l2 + W_SSIM * ssim + W_FOCAL * focal, l2, ssim, focal)
