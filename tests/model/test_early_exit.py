"""Early exit of the per-prior ensemble: the exact rule never changes a decision; the margin rule saves more."""

from __future__ import annotations

import numpy as np
import pytest
import torch
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.draem.early_exit import decided, simulate


def test_decided_cases() -> None:
    assert not decided([], 3, 0.5)
    assert decided([0.9, 0.9, 0.0], 3, 0.5)  # all members run
    assert decided([0.9, 0.7], 3, 0.5)  # 1.6 / 3 > 0.5 whatever the third says
    assert not decided([0.9, 0.5], 3, 0.5)  # the third could pull the mean to 0.47
    assert decided([0.0], 3, 0.7)  # (0 + 2) / 3 <= 0.7: cannot reach the threshold
    assert not decided([0.1], 3, 0.5) and decided([0.1], 3, 0.5, margin=0.3)  # running mean 0.4 away


@settings(max_examples=200, deadline=None)
@given(arrays(np.float64, st.tuples(st.integers(1, 20), st.integers(1, 4)), elements=st.floats(0, 1)),
       st.floats(0, 1), st.floats(0.01, 0.5))
def test_exact_rule_keeps_every_decision(scores: np.ndarray, threshold: float, margin: float) -> None:
    full = scores.mean(1) > threshold
    early, used = simulate(scores, threshold)
    assert ((early > threshold) == full).all()
    assert ((1 <= used) & (used <= scores.shape[1])).all()
    _, used_margin = simulate(scores, threshold, margin)
    assert (used_margin <= used).all()  # the margin rule stops at least as early


def test_detector_runs_only_the_members_asked() -> None:
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "ensemble", 32)).eval()
    det.init_weights(torch.Generator().manual_seed(0))
    x = torch.rand(2, 4, 32, 32, generator=torch.Generator().manual_seed(1))
    full = det.predict(x)
    one = det.predict(x, members=("dolp",))
    assert list(one.member_scores) == ["dolp"]
    assert torch.allclose(one.score, full.member_scores["dolp"])
    assert torch.allclose(one.anomaly_map, full.member_maps["dolp"])
    with pytest.raises(KeyError):
        det.predict(x, members=("normal",))
