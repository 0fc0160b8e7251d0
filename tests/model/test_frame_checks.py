"""What a frame check beyond its limit says in a reject's reason (``model.draem.frame_checks.beyond_limits``)."""

from __future__ import annotations

import math

from model.draem.frame_checks import EDGE_BEND_LIMIT, MAX_HIDDEN, NOISE_CAP, UNSEEN_LIMIT, beyond_limits


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
