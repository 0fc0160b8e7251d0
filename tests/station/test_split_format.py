"""``station split``'s printed report: it says when the second camera does not pay for its share of the budget."""

from station.commands.split import format_split


def _report(split_caught: float) -> dict:
    """A split report as ``station.evaluation.split_camera_thresholds`` returns it (plan 6's validation reading:
    727 good parts, a budget of 5, the first camera alone catching 71.9 % at its own threshold)."""
    return {"parts": 1200, "good": 727, "defective": 473, "budget": 5, "rate": 0.01, "expected": True,
            "first": {"data": "line"}, "left_out": {}, "chosen": 0, "chosen_good_above": {"first": 5, "second": 0},
            "splits": [{"k": 0, "first": 0.9864, "second": 0.9979, "good_rejected": 5, "caught": split_caught}],
            "alone": {"first": {"threshold": 0.9785, "good_rejected": 7 / 727, "caught": 0.719},
                      "second": {"threshold": 0.9966, "good_rejected": 7 / 727, "caught": 0.207}}}


def test_a_split_that_catches_no_more_than_the_first_camera_alone_is_called_out():
    text = format_split(_report(0.700))
    assert ("the first camera alone catches at least as many here (71.9 % at 1.0 % of good parts rejected) as the "
            "chosen split (70.0 % at 0.7 %): on these parts the second camera does not pay for its share of the budget"
            in text)


def test_a_split_that_catches_more_says_nothing_of_it():
    assert "does not pay" not in format_split(_report(0.823))
