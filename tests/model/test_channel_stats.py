"""channel_stats tells a smooth channel from pixel noise and maps channels to the right ensemble member."""

import pytest
import torch

from model.draem.channel_stats import CHANNEL_NAMES, adjacent_correlation, channel_names, channel_stats
from model.draem.config import PRIOR_CHANNELS, ModelConfig
from model.draem.detector import Detector
from model.draem.errors import ModelError


def test_channel_names_follow_the_stacking_order():
    assert {p: len(c) for p, c in CHANNEL_NAMES.items()} == PRIOR_CHANNELS
    assert channel_names(("intensity", "aolp", "dolp")) == ["intensity", "aolp_cos", "aolp_sin", "dolp"]


def test_adjacent_correlation_smooth_noise_and_constant():
    g = torch.Generator().manual_seed(0)
    yy, xx = torch.meshgrid(torch.linspace(0, 1, 32), torch.linspace(0, 1, 32), indexing="ij")
    smooth = torch.sin(6 * xx + 3 * yy)[None].repeat(4, 1, 1)
    noise = torch.randn(4, 32, 32, generator=g)
    mask = torch.ones(4, 32, 32, dtype=torch.bool)
    assert adjacent_correlation(smooth, mask) > 0.95
    assert abs(adjacent_correlation(noise, mask)) < 0.1
    assert adjacent_correlation(torch.ones(4, 32, 32), mask) is None
    # only pairs inside the mask count: a mask of isolated pixels leaves none
    checker = (torch.arange(32)[None, :] % 2 == 0).expand(4, 32, 32)
    assert adjacent_correlation(noise, checker) is None


@pytest.mark.parametrize("fusion", ["ensemble", "fused"])
def test_channel_stats_per_channel(fusion):
    torch.manual_seed(0)
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "aolp"), fusion, 32)).eval()
    yy, xx = torch.meshgrid(torch.linspace(0, 1, 32), torch.linspace(0, 1, 32), indexing="ij")
    a = torch.randn(3, 32, 32) * 3
    x = torch.stack([(xx + yy)[None].repeat(3, 1, 1), torch.cos(a), torch.sin(a)], 1)
    mask = torch.zeros(3, 32, 32, dtype=torch.bool)
    mask[:, 4:28, 4:28] = True
    stats = channel_stats(det, x, mask, batch_size=2)
    assert [s.channel for s in stats] == ["intensity", "aolp_cos", "aolp_sin"]
    assert stats[0].adjacent_corr > 0.95 and all(abs(s.adjacent_corr) < 0.3 for s in stats[1:])
    assert all(s.variance > 0 and s.unexplained is not None and s.unexplained >= 0 for s in stats)


def test_channel_stats_needs_eval_mode_and_object_pixels():
    det = Detector(ModelConfig.from_preset("tiny", ("intensity",), "fused", 32))
    x = torch.rand(2, 1, 32, 32)
    with pytest.raises(ModelError, match="eval mode"):
        channel_stats(det, x, torch.ones(2, 32, 32, dtype=torch.bool))
    with pytest.raises(ModelError, match="no object pixels"):
        channel_stats(det.eval(), x, torch.zeros(2, 32, 32, dtype=torch.bool))
