from __future__ import annotations

import contextlib
from collections.abc import Iterator

import pytest
import torch


def toy_priors(n: int = 12, size: int = 64, seed: int = 0) -> tuple[torch.Tensor, torch.Tensor]:
    """A disc-shaped 'part' with smooth intensity, DoLP and radial AoLP plus noise: (N, 4, S, S), (N, S, S)."""
    g = torch.Generator().manual_seed(seed)
    yy, xx = torch.meshgrid(torch.linspace(-1, 1, size), torch.linspace(-1, 1, size), indexing="ij")
    obj = ((yy**2 + xx**2) < 0.6).expand(n, size, size).clone()
    inten = (0.4 + 0.1 * torch.sin(6 * xx) + 0.02 * torch.randn(n, size, size, generator=g)).clamp(0, 1)
    dolp = (0.1 + 0.05 * yy).expand(n, size, size)
    ang = torch.atan2(yy, xx).expand(n, size, size)
    x = torch.stack([inten, dolp, torch.cos(2 * ang), torch.sin(2 * ang)], 1).float()
    return x, obj


@pytest.fixture
def toy():
    return toy_priors


THREADS = 2
"""torch threads for every model test and module fixture: the same steps then train the same network whatever ran
before in the process."""


@contextlib.contextmanager
def _threads(n: int) -> Iterator[None]:
    old = torch.get_num_threads()
    torch.set_num_threads(n)
    try:
        yield
    finally:
        torch.set_num_threads(old)


@pytest.fixture(autouse=True)
def _few_threads() -> Iterator[None]:
    with _threads(THREADS):
        yield


@pytest.fixture(scope="module", autouse=True)
def _few_threads_for_module_fixtures() -> Iterator[None]:
    """The same threads while a module's fixtures train (they run before ``_few_threads``; under two pytest workers
    test_residual_look's look once trained at another count and raised no score)."""
    with _threads(THREADS):
        yield
