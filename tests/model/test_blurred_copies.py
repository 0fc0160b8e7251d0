"""``model.draem.shifts.blurred_copies``: the good parts as a softer lens would show them, for the variation model's
fit; one copy per part, each the shift bench's blur of its part at a drawn sigma, the same draws for the same seed."""

from __future__ import annotations

import numpy as np
import pytest

from model.draem.shifts import Channels, blurred_copies, shift

CH = Channels(intensity=0, dolp=1, aolp=2)


def sharp_parts(n: int = 6) -> np.ndarray:
    """(n, 4, 16, 24): a bright, polarized square on a dark belt (a silhouette for the blur to soften)."""
    x = np.zeros((n, 4, 16, 24), np.float32)
    x[:, 0], x[:, 2] = 0.05, 1.0
    x[:, 0, 4:12, 6:18], x[:, 1, 4:12, 6:18] = 0.6, 0.3
    return x


def test_one_copy_per_part_each_its_part_blurred_at_a_drawn_sigma() -> None:
    x = sharp_parts()
    copies = blurred_copies(x, CH, 1.5, seed=3)
    assert copies.shape == x.shape and np.isfinite(copies).all()
    sigmas = np.random.default_rng(3).uniform(0.0, 1.5, len(x))
    for i, s in enumerate(sigmas):  # each is the bench's blur of its own part
        assert np.allclose(copies[i], shift(f"blur {s:.4f} px", x[i:i + 1], CH)[0], atol=1e-6)
    assert not np.array_equal(copies, x)  # the silhouettes softened
    # the same draws for the same seed (OpenCV's blur is the same to float rounding, 1e-7, not bit for bit)
    assert np.allclose(blurred_copies(x, CH, 1.5, seed=3), copies, atol=1e-6)
    assert not np.allclose(blurred_copies(x, CH, 1.5, seed=4), copies, atol=1e-3)
    assert np.array_equal(blurred_copies(x, CH, 0.0), x)  # no blur: the parts themselves


def test_a_bad_sigma_is_refused() -> None:
    for bad in (-1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="max_sigma"):
            blurred_copies(sharp_parts(), CH, bad)
