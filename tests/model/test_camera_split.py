"""Two cameras, one decision: the split of the budget of good parts rejected (``model.draem.camera_split``)."""

from __future__ import annotations

import numpy as np
import pytest

from model.draem.camera_split import expected_budget, split_rejects, split_thresholds
from model.draem.metrics import false_reject_threshold
from model.draem.rate_bounds import either_rate


def parts(seed: int = 0, n_good: int = 400, n_front: int = 60, n_top: int = 140):
    """Good parts; front-face defects the first camera sees weakly and the second well; top-face defects only the
    first sees. Scores in [0, 1], higher more anomalous."""
    rng = np.random.default_rng(seed)
    n = n_good + n_front + n_top
    y = np.r_[np.zeros(n_good, bool), np.ones(n_front + n_top, bool)]
    first = np.r_[rng.beta(2, 8, n_good), rng.beta(3, 5, n_front), rng.beta(6, 2, n_top)]
    second = np.r_[rng.beta(2, 8, n_good), rng.beta(8, 2, n_front), rng.beta(2, 8, n_top)]
    assert first.size == second.size == n
    return y, first, second


def test_every_split_keeps_the_budget_and_the_chosen_one_catches_the_most() -> None:
    y, first, second = parts()
    rows, best = split_thresholds(y, first, second, 0.01)
    assert [r.k for r in rows] == [0, 1, 2, 3, 4]  # budget: 4 of 400 good parts
    for r in rows:
        rejected = split_rejects(first, second, r)
        assert rejected[~y].sum() == r.good_rejected <= 4 and (second[~y] > r.second).sum() == r.k
        assert rejected[y].mean() == pytest.approx(r.caught)
    assert rows[best].caught == max(r.caught for r in rows)
    # the first camera alone at the same rate catches less: the second sees the front faces
    alone = first[y] > false_reject_threshold(first[~y], 0.01)
    assert rows[best].caught > alone.mean() + 0.1


def test_a_second_camera_that_sees_nothing_leaves_the_budget_to_the_first() -> None:
    y, first, _ = parts(1)
    second = np.random.default_rng(2).uniform(0, 1, y.size)  # noise: sees no defect
    rows, best = split_thresholds(y, first, second, 0.01)
    chosen = rows[best]
    assert chosen.k == 0 and chosen.first == false_reject_threshold(first[~y], 0.01)
    assert chosen.second == second[~y].max()  # no good part above it


def test_the_expected_budget_holds_the_rate_for_new_good_parts_on_average() -> None:
    """Two cameras' thresholds, each from independent good scores: over many validation sets, the share of new good
    parts either rejects stays at or under the rate on average at ``expected_budget``, and goes over it at the
    count's budget (floor(rate x n))."""
    assert [expected_budget(n, 0.01) for n in (368, 725, 1000)] == [1, 5, 8]
    rng = np.random.default_rng(5)
    shares: dict[str, list[float]] = {"count": [], "expected": []}
    for _ in range(400):
        y = np.zeros(368, bool)
        a, b = rng.random(368), rng.random(368)
        for mode in shares:
            budget = expected_budget(368, 0.01) if mode == "expected" else None
            rows, best = split_thresholds(y, a, b, 0.01, budget)
            new_a, new_b = rng.random(3000), rng.random(3000)
            shares[mode].append(float(split_rejects(new_a, new_b, rows[best]).mean()))
            if mode == "expected":
                above = [int((a > rows[best].first).sum()), int((b > rows[best].second).sum())]
                assert sum(above) <= 1 and either_rate(above, 368)[0] <= 0.01
    assert np.mean(shares["expected"]) <= 0.01 < np.mean(shares["count"])
    with pytest.raises(ValueError, match=r"198 good parts cannot hold 1.00% .* needs 199 or more"):
        expected_budget(198, 0.01)
    assert expected_budget(199, 0.01) == 0


def test_bad_inputs_are_refused() -> None:
    y, first, second = parts()
    with pytest.raises(ValueError, match="labels"):
        split_thresholds(y[:-1], first, second)
    with pytest.raises(ValueError, match="no good parts"):
        split_thresholds(np.ones(3, bool), np.zeros(3), np.zeros(3))
    with pytest.raises(ValueError, match="NaN"):
        split_thresholds(y, np.r_[first[:-1], np.nan], second)
    with pytest.raises(ValueError, match="rate"):
        split_thresholds(y, first, second, 1.0)
    with pytest.raises(ValueError, match="budget"):
        split_thresholds(y, first, second, 0.01, -1)
