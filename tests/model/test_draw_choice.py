"""``model.draem.draw_choice``: the draw rejecting fewest good parts is kept; ties go to more defective caught,
then to the first named; a score that is not a number is a rejection; a choice needs two draws on one set."""

from __future__ import annotations

import numpy as np
import pytest

from model.draem.draw_choice import DrawCounts, choose_draw, draw_counts

LABELS = np.array([0, 0, 0, 0, 1, 1])


def test_counts_reject_above_the_threshold_and_every_nan() -> None:
    c = draw_counts("a", 0.5, LABELS, np.array([0.1, 0.5, 0.6, np.nan, 0.9, 0.4]))
    assert (c.good, c.good_rejected, c.defective, c.caught) == (4, 2, 2, 1)  # 0.5 is at the threshold: passed
    with pytest.raises(ValueError, match="5 scores"):
        draw_counts("a", 0.5, LABELS, np.zeros(5))


def test_fewest_good_rejected_then_most_caught_then_first_named() -> None:
    def c(name: str, good_rejected: int, caught: int) -> DrawCounts:
        return DrawCounts(name, 0.5, 100, good_rejected, 40, caught)

    assert choose_draw([c("s", 14, 30), c("r", 51, 33), c("r2", 4, 29)]).kept_name == "r2"
    assert choose_draw([c("s", 4, 30), c("r", 4, 33)]).kept_name == "r"  # a tie: more caught
    choice = choose_draw([c("s", 4, 30), c("r", 4, 30)])
    assert choice.kept == 0 and [d.name for d in choice.counts] == ["s", "r"]  # a tie of both: the first named


def test_a_choice_needs_two_draws_on_one_set_of_good_parts() -> None:
    one = DrawCounts("a", 0.5, 10, 1, 2, 2)
    with pytest.raises(ValueError, match="at least two"):
        choose_draw([one])
    with pytest.raises(ValueError, match="different numbers of good parts"):
        choose_draw([one, DrawCounts("b", 0.5, 11, 1, 2, 2)])
    with pytest.raises(ValueError, match="no good parts"):
        choose_draw([DrawCounts("a", 0.5, 0, 0, 2, 2), DrawCounts("b", 0.5, 0, 0, 2, 1)])
