"""What a frame check beyond its limit says in a reject's reason (``model.draem.frame_checks.beyond_limits``)."""

from __future__ import annotations

import math

from model.draem.frame_checks import EDGE_BEND_LIMIT, MAX_HIDDEN, NOISE_CAP, TURN_LIMIT_DEG, UNSEEN_LIMIT, beyond_limits


def test_each_check_beyond_its_limit_says_so_and_none_within_or_missing_or_nan():
    assert beyond_limits({}) == []
    assert beyond_limits({"highlight_fraction": MAX_HIDDEN, "noise_level": NOISE_CAP, "edge_bend": -EDGE_BEND_LIMIT,
                          "unseen_fraction": UNSEEN_LIMIT}) == []  # at a limit: within it
    assert beyond_limits({"highlight_fraction": math.nan, "noise_level": math.nan, "edge_bend": math.nan}) == []
    said = beyond_limits({"highlight_fraction": 0.62, "noise_level": 3.4, "edge_bend": -1.6, "unseen_fraction": 0.034})
    assert said[-1] == ("3.4 % of the part lay outside the model's view as registered, read from the frame's border "
                        "there (camera turned from square or the part off its place)")
    assert beyond_limits({"unseen_fraction": 0.00074}) == [
        "0.074 % of the part lay outside the model's view as registered, read from the frame's border there (camera "
        "turned from square or the part off its place)"]
    assert said[:-1] == ["highlights cover 62 % of the part (over 50 %: judged with them, as a part unlike the model's "
                    "line)",
                    "the frame is 3.4 times as noisy as the model's good parts (over 3: judged unscaled, as a part "
                    "unlike the model's line)",
                    "shape check: the bottom edge bends 1.6 times as far as any good part's"]


def test_a_part_turned_past_the_limit_says_how_far_and_one_within_or_unread_says_nothing():
    """``turn_deg`` beyond +-``TURN_LIMIT_DEG`` (24: the largest good part's turn where the shipped file held a camera
    turned 20 degrees) names the turn in a reject's reason, either way; at the limit, NaN or missing, nothing."""
    assert TURN_LIMIT_DEG == 24.0
    assert beyond_limits({"turn_deg": -26.4}) == [
        "the part lay turned -26 degrees from the model's good parts (beyond 24: camera turned from square or the part "
        "off its place)"]
    assert beyond_limits({"turn_deg": 31.0})[0].startswith("the part lay turned +31 degrees")
    assert beyond_limits({"turn_deg": -TURN_LIMIT_DEG}) == beyond_limits({"turn_deg": math.nan}) == []
