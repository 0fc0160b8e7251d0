"""DRAEM (Zavrtanik et al., ICCV 2021) as published, with widths, input channels and input size as config.

Reconstructive sub-network: encoder-decoder without skips, base width ``w`` (paper: 128). The encoder has five
double-conv blocks of widths (w, 2w, 4w, 8w, 8w) with four 2x max-pools; the decoder four (bilinear up-sample,
conv) steps, each followed by a double conv that halves the width, and a 3x3 output conv back to ``C`` channels.

Discriminative sub-network: U-Net with skips, base width ``v`` (paper: 64), input = the (possibly anomalous) prior
and its reconstruction concatenated (2C channels); encoder widths (v, 2v, 4v, 8v, 8v, 8v) with five pools, decoder
mirrors it with skip concatenations; output 2 logits per pixel (normal, anomalous), read through a softmax.

Every conv is 3x3, padding 1, followed by BatchNorm and ReLU (except the output convs). Parameter count for the
paper widths with 3 input channels: 69.0 M (reconstructive) + 28.4 M (discriminative), as in the official code.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import torch
import torch.nn.functional as F
from torch import nn

from .config import NetworkConfig


def _conv_bn_relu(c_in: int, c_out: int) -> list[nn.Module]:
    return [nn.Conv2d(c_in, c_out, 3, padding=1), nn.BatchNorm2d(c_out), nn.ReLU(inplace=True)]


def _double_conv(c_in: int, c_mid: int, c_out: int | None = None) -> nn.Sequential:
    return nn.Sequential(*_conv_bn_relu(c_in, c_mid), *_conv_bn_relu(c_mid, c_out or c_mid))


def _up_conv(c_in: int, c_out: int) -> nn.Sequential:
    return nn.Sequential(nn.Upsample(scale_factor=2, mode="bilinear", align_corners=True), *_conv_bn_relu(c_in, c_out))


class ReconstructiveSubNetwork(nn.Module):
    """(N, C, H, W) -> (N, C, H, W) reconstruction; H, W multiples of 16."""

    def __init__(self, in_channels: int, base_width: int = 128):
        super().__init__()
        w = base_width
        widths = (w, 2 * w, 4 * w, 8 * w, 8 * w)
        self.encoder = nn.ModuleList(
            [_double_conv(c_in, c_out) for c_in, c_out in zip((in_channels, *widths[:-1]), widths, strict=True)])
        # decoder: (up-sample width, double conv out width); the last stage keeps w
        self.decoder = nn.ModuleList()
        for c_in, c_out in ((8 * w, 4 * w), (4 * w, 2 * w), (2 * w, w), (w, w)):
            self.decoder.append(nn.Sequential(_up_conv(c_in, c_in), _double_conv(c_in, c_in, c_out)))
        self.out = nn.Conv2d(w, in_channels, 3, padding=1)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        for i, block in enumerate(self.encoder):
            x = block(x if i == 0 else F.max_pool2d(x, 2))
        for block in self.decoder:
            x = block(x)
        return self.out(x)


class DiscriminativeSubNetwork(nn.Module):
    """(N, 2C, H, W) -> (N, 2, H, W) logits (channel 1 = anomalous); H, W multiples of 32."""

    def __init__(self, in_channels: int, base_width: int = 64, out_channels: int = 2):
        super().__init__()
        v = base_width
        widths = (v, 2 * v, 4 * v, 8 * v, 8 * v, 8 * v)
        self.encoder = nn.ModuleList(
            [_double_conv(c_in, c_out) for c_in, c_out in zip((in_channels, *widths[:-1]), widths, strict=True)])
        self.up = nn.ModuleList()
        self.fuse = nn.ModuleList()
        # (from width, skip width, out width), deepest first: b6 -> b5 -> b4 -> b3 -> b2 -> b1
        for c_from, c_skip, c_out in ((8 * v, 8 * v, 8 * v), (8 * v, 8 * v, 4 * v), (4 * v, 4 * v, 2 * v),
                                      (2 * v, 2 * v, v), (v, v, v)):
            self.up.append(_up_conv(c_from, c_out))
            self.fuse.append(_double_conv(c_out + c_skip, c_out))
        self.out = nn.Conv2d(v, out_channels, 3, padding=1)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        skips = []
        for i, block in enumerate(self.encoder):
            x = block(x if i == 0 else F.max_pool2d(x, 2))
            skips.append(x)
        x = skips.pop()
        for up, fuse in zip(self.up, self.fuse, strict=True):
            x = fuse(torch.cat((up(x), skips.pop()), dim=1))
        return self.out(x)


@dataclass
class DraemTrainOutput:
    """reconstruction: (N, C, H, W) in normalised prior units; logits: (N, 2, H, W), channel 1 = anomalous."""

    reconstruction: torch.Tensor
    logits: torch.Tensor


@dataclass
class DraemEvalOutput:
    """reconstruction: (N, C, H, W); anomaly_map: (N, H, W) softmax probability of "anomalous" in [0, 1]."""

    reconstruction: torch.Tensor
    anomaly_map: torch.Tensor


class Draem(nn.Module):
    """Both sub-networks. ``forward`` returns ``DraemTrainOutput`` in train mode, ``DraemEvalOutput`` in eval mode.

    Input: (N, C, S, S) normalised priors, S = ``config.input_size_px``. The discriminative network sees the input
    and its reconstruction (detached in eval mode only: in training both losses reach the reconstructive net
    through the discriminative input too, as in the official code)."""

    def __init__(self, config: NetworkConfig):
        super().__init__()
        self.config = config
        self.reconstructive = ReconstructiveSubNetwork(config.in_channels, config.reconstructive_width)
        self.discriminative = DiscriminativeSubNetwork(2 * config.in_channels, config.discriminative_width)

    def forward(self, x: torch.Tensor) -> DraemTrainOutput | DraemEvalOutput:
        if x.ndim != 4 or x.shape[1] != self.config.in_channels:
            raise ValueError(f"DRAEM input must be (N, {self.config.in_channels}, H, W), got {tuple(x.shape)}")
        rec = self.reconstructive(x)
        if not self.training:
            rec = rec.detach()
        logits = self.discriminative(torch.cat((rec, x), dim=1))
        if self.training:
            return DraemTrainOutput(rec, logits)
        return DraemEvalOutput(rec, torch.softmax(logits.float(), dim=1)[:, 1])


def init_weights(module: nn.Module, generator: torch.Generator | None = None) -> None:
    """DRAEM's initialisation: conv weights N(0, 0.02), BatchNorm scale N(1, 0.02) and shift 0; conv biases keep
    PyTorch's default law U(-1/sqrt(fan_in), 1/sqrt(fan_in)) but are redrawn from ``generator`` so the whole
    initialisation depends on the seed only."""
    for m in module.modules():
        if isinstance(m, nn.Conv2d):
            with torch.no_grad():
                m.weight.normal_(0.0, 0.02, generator=generator)
                if m.bias is not None:
                    bound = 1.0 / math.sqrt(m.in_channels // m.groups * m.kernel_size[0] * m.kernel_size[1])
                    m.bias.uniform_(-bound, bound, generator=generator)
        elif isinstance(m, nn.BatchNorm2d):
            with torch.no_grad():
                m.weight.normal_(1.0, 0.02, generator=generator)
                m.bias.zero_()


def count_parameters(module: nn.Module) -> int:
    return sum(p.numel() for p in module.parameters())
