"""Polarization noise as a training augmentation: it raises DoLP as noise does (the bias a noisier line or renderer
shows), keeps every prior in its range, is seeded, and in a batch changes the inputs but never the clean targets."""

from __future__ import annotations

import pytest
import torch

from model.draem.anomaly import AnomalyConfig
from model.draem.errors import ModelError
from model.draem.mixed import draw_batch
from model.draem.polarization_noise import add_polarization_noise
from model.draem.train import TensorData, TrainConfig
from tests.model.conftest import toy_priors

PRIORS = ("intensity", "dolp", "aolp")


def weakly_polarized(n: int = 16) -> torch.Tensor:
    x = torch.zeros(n, 4, 16, 32)
    x[:, 0], x[:, 1], x[:, 2] = 0.3, 0.1, 1.0  # DoLP 0.1 at AoLP 0
    return x


def test_noise_raises_dolp_like_the_length_of_a_noisy_vector_and_keeps_ranges() -> None:
    x = weakly_polarized()
    y = add_polarization_noise(x, PRIORS, 0.1, torch.Generator().manual_seed(0))
    assert torch.equal(y[:, 0], x[:, 0])  # intensity untouched
    assert bool(torch.isfinite(y).all()) and bool(((y[:, 1] >= 0) & (y[:, 1] <= 1)).all())
    assert torch.allclose(y[:, 2] ** 2 + y[:, 3] ** 2, torch.ones(16, 16, 32), atol=1e-5)
    levels = y[:, 1].mean((1, 2))
    # sigma ~ U(0, 0.1) per sample: every sample's DoLP goes up (E|s + n| >= |s|), the noisiest by several 0.01
    assert bool((levels > 0.099).all()) and float(levels.max()) > 0.12
    again = add_polarization_noise(x, PRIORS, 0.1, torch.Generator().manual_seed(0))
    assert torch.equal(y, again)


def test_no_noise_or_no_dolp_leaves_the_input_alone() -> None:
    x = weakly_polarized()
    assert add_polarization_noise(x, PRIORS, 0.0, torch.Generator()) is x
    only_i = x[:, :1]
    assert add_polarization_noise(only_i, ("intensity",), 0.1, torch.Generator()) is only_i


def test_a_noisy_batch_keeps_clean_targets() -> None:
    x, obj = toy_priors(6, 32)
    data = TensorData(x, obj)

    def batch(noise: float):
        return draw_batch(data, PRIORS, 4, torch.Generator().manual_seed(1), torch.Generator().manual_seed(2),
                          AnomalyConfig(), torch.device("cpu"), polarization_noise=noise)

    clean, noisy = batch(0.0), batch(0.1)
    assert torch.equal(clean.target, noisy.target)  # the parts as they are: what the reconstruction aims at
    assert not torch.equal(clean.inputs[:, 1], noisy.inputs[:, 1])  # the inputs' DoLP changed
    with pytest.raises(ModelError, match="polarization_noise"):
        TrainConfig(polarization_noise=-0.1)
