"""model.draem.vectors.unit_vectors: F.normalize's values without its CPU cost, and no NaN at zero."""

from __future__ import annotations

import torch
import torch.nn.functional as F

from model.draem.vectors import unit_vectors


def test_matches_f_normalize_including_tiny_vectors() -> None:
    g = torch.Generator().manual_seed(0)
    v = torch.randn(4, 3, 16, 16, generator=g)
    v[0, :, 0, 0] = 0.0
    v[1, :, 2, 3] = 1e-8  # below eps: F.normalize divides by eps
    torch.testing.assert_close(unit_vectors(v, 1), F.normalize(v, dim=1, eps=1e-6), rtol=1e-6, atol=1e-6)
    norms = unit_vectors(v, 1).square().sum(1)
    assert torch.allclose(norms[norms > 0.5], torch.ones(()), atol=1e-6)


def test_fallback_replaces_only_short_vectors() -> None:
    v = torch.tensor([[3.0, 0.0], [4.0, 0.0], [0.0, 0.0]])  # (3, 2): two vectors along dim 0, the second zero
    fb = torch.tensor([[0.0], [0.0], [1.0]])
    out = unit_vectors(v, 0, fallback=fb)
    torch.testing.assert_close(out[:, 0], torch.tensor([0.6, 0.8, 0.0]))
    torch.testing.assert_close(out[:, 1], torch.tensor([0.0, 0.0, 1.0]))


def test_gradient_is_finite_at_the_zero_vector() -> None:
    v = torch.zeros(1, 3, 2, 2, requires_grad=True)
    unit_vectors(v, 1).sum().backward()
    assert torch.isfinite(v.grad).all()
