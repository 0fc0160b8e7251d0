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


def test_what_the_models_checks_found_follows_a_rejects_score_and_nothing_else():
    found = ["shape check: the bottom edge bends 1.6 times as far as any good part's"]
    d = decide(0.51, 0.5, found=found)
    assert d.decision == "reject" and d.reason == f"score 0.5100 > threshold 0.5000; {found[0]}"
    assert decide(0.4, 0.5, found=found).reason is None  # a pass has no reason
    assert decide(0.9, 0.5, error="camera error", found=found).reason == "not judged: camera error"


def test_within_budget_and_few_invalid_pixels_still_passes():
    assert decide(0.1, 0.5, elapsed_ms=99.0, cycle_time_ms=100.0, invalid_fraction=0.001).decision == "pass"


def test_a_threshold_chosen_on_validation_passes_the_good_part_that_set_it_and_rejects_every_part_above():
    """The threshold is a good validation part's own score (the budget's bound) and the station rejects at
    score > t: that good part passes, as choose_threshold counted it, and every part above it is rejected. (When the
    rule was F1-max, which counts score >= t, its threshold was a defective part's score, and the station passed
    that part: choose_threshold now hands the station strict thresholds only.)"""
    import numpy as np

    from model.draem.metrics import choose_threshold

    labels, scores = np.array([0, 0, 0, 0, 1]), np.array([0.1, 0.2, 0.3, 0.35, 0.36])
    choice = choose_threshold(labels, scores, max_good_flagged=0.0)
    assert choice.threshold == 0.35 and choice.detected_fraction == 1.0 and choice.flagged_good_fraction == 0.0
    assert decide(0.36, choice.threshold).decision == "reject"
    assert decide(0.35, choice.threshold).decision == "pass"
    choice = choose_threshold(labels, scores, max_good_flagged=0.25)  # one of four good parts may be rejected
    assert choice.threshold == 0.3 and decide(0.35, choice.threshold).decision == "reject"


def test_verdicts_are_their_strings_on_the_wire_and_in_json():
    import json

    from drivers.line_io import Command, Verdict, decision_line

    assert [v.value for v in Verdict] == ["pass", "reject", "empty", "not_inspected"]
    assert decide(0.2, 0.5).decision is Verdict.PASS and decide(0.9, 0.5).decision is Verdict.REJECT
    for verdict, text in ((Verdict.PASS, "pass"), (Verdict.REJECT, "reject")):
        assert verdict == text and f"{verdict}" == text and json.dumps({"d": verdict}) == json.dumps({"d": text})
        assert decision_line("P7", verdict, "score high") == decision_line("P7", text, "score high")
    assert decision_line("P7", Verdict.PASS, None) == b"PASS P7\n"
    assert decision_line("P7", Verdict.NOT_INSPECTED, "queue full") == b"REJECT P7 queue_full\n"  # fail closed
    assert [c.value for c in Command] == ["TRIG", "ACK", "HB", "ERR", "PASS", "REJECT"]
