"""Fail closed: every way a part can escape judgement ends in a reject with its reason."""

from __future__ import annotations

import pytest

from station.decision import decide


def test_score_against_threshold():
    assert decide(0.2, 0.5).decision == "pass" and decide(0.5, 0.5).decision == "pass"
    d = decide(0.51, 0.5)
    assert d.decision == "reject" and d.reason == "score 0.5100 > threshold 0.5000"


@pytest.mark.parametrize(("kwargs", "reason"), [
    ({"score": float("nan")}, "model score is nan"),
    ({"score": None}, "model score is None"),
    ({"score": float("inf")}, "model score is inf"),
    ({"score": -0.25}, "model score is -0.25"),
    ({"score": 0.1, "error": "decode error: frame 17 truncated"}, "decode error: frame 17"),
    ({"score": 0.1, "invalid_fraction": 0.2}, "20.00 % of input pixels invalid"),
    ({"score": 0.1, "elapsed_ms": 140.0, "cycle_time_ms": 100.0}, "140.0 ms > cycle time 100.0 ms"),
])
def test_unjudgeable_parts_are_rejected_with_a_reason(kwargs, reason):
    d = decide(threshold=0.5, **kwargs)
    assert d.decision == "reject" and reason in d.reason


def test_within_budget_and_few_invalid_pixels_still_passes():
    assert decide(0.1, 0.5, elapsed_ms=99.0, cycle_time_ms=100.0, invalid_fraction=0.001).decision == "pass"
