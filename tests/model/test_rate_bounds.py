"""The exact bounds on a share counted on finite sets (model/draem/rate_bounds.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from model.draem.metrics import choose_threshold
from model.draem.rate_bounds import either_rate, expected_rate, interval, parts_needed, upper_bound


def test_zero_of_n_has_the_closed_form_bound_and_the_rule_of_three():
    for n in (10, 100, 370, 1000):
        assert upper_bound(0, n, 0.95) == pytest.approx(1.0 - 0.05 ** (1.0 / n), rel=1e-9)
    assert 300 * upper_bound(0, 300) == pytest.approx(3.0, rel=0.01)  # about 3 / n
    assert upper_bound(5, 5) == 1.0 and interval(0, 5)[0] == 0.0 and interval(5, 5)[1] == 1.0


def test_the_interval_holds_its_coverage_on_binomial_draws():
    rng = np.random.default_rng(0)
    for p, n in ((0.01, 370), (0.2, 50)):
        k = rng.binomial(n, p, size=4000)
        inside = np.mean([lo <= p <= hi for lo, hi in (interval(int(x), n) for x in k)])
        above = np.mean([upper_bound(int(x), n) >= p for x in k])
        assert inside >= 0.95 and above >= 0.95  # exact: at least the nominal coverage
        assert inside < 0.995  # and not vacuous


def test_the_bound_is_the_quantile_of_new_good_parts_above_the_stations_threshold():
    """Set a threshold by the station's rule on n good scores, count new good parts above it: over many lines,
    95 % of them see a share at or under ``upper_bound(k, n)``, and the mean share is ``expected_rate``."""
    def squash(x):  # scores in [0, 1), as the station's are
        return x / (1.0 + np.abs(x)) / 2.0 + 0.5

    rng = np.random.default_rng(1)
    n, m, shares = 370, 2000, []
    for _ in range(1500):
        val = squash(rng.standard_t(3, n))  # heavy-tailed: the bound does not depend on the scores' distribution
        t = choose_threshold(np.zeros(n), val, 0.01).threshold
        assert (val > t).sum() == 3
        shares.append(float((squash(rng.standard_t(3, m)) > t).mean()))
    assert np.mean(shares) == pytest.approx(expected_rate(3, n), rel=0.06)
    assert np.quantile(shares, 0.95) == pytest.approx(upper_bound(3, n), rel=0.08)
    assert 0.0205 < upper_bound(3, n) < 0.021  # the shipped rule on 370 good parts: up to 2.1 % on new parts


def test_two_cameras_thresholds_bound_the_share_rejected_by_either():
    """Two cameras' independent good scores on the same n parts, each threshold with 1 above it (2 by either):
    new good parts are rejected by either at a share whose mean and 95th percentile lie under ``either_rate``'s,
    and above what one threshold with 2 above it would say."""
    rng = np.random.default_rng(2)
    n, m, shares = 368, 2000, []
    for _ in range(1000):
        a, b = rng.random(n), rng.random(n)
        ta, tb = np.sort(a)[-2], np.sort(b)[-2]  # one part above each
        shares.append(float(((rng.random(m) > ta) | (rng.random(m) > tb)).mean()))
    mean, bound = either_rate([1, 1], n)
    assert np.mean(shares) <= mean and np.quantile(shares, 0.95) <= bound
    assert np.mean(shares) > expected_rate(2, n) * 1.2  # two thresholds are not one with the union's count
    assert either_rate([3], n) == (expected_rate(3, n), upper_bound(3, n))


def test_parts_needed_is_the_smallest_n_that_bounds_the_rate():
    for k in (0, 3):
        n = parts_needed(0.01, 0.95, k)
        assert upper_bound(k, n) <= 0.01 < upper_bound(k, n - 1)
    assert parts_needed(0.01) == math.ceil(math.log(0.05) / math.log(0.99)) == 299
    assert parts_needed(0.01, k=3) == 773


@pytest.mark.parametrize("call", [lambda: upper_bound(4, 3), lambda: upper_bound(0, 0), lambda: interval(1, 10, 1.0),
                                  lambda: parts_needed(0.0), lambda: parts_needed(0.01, k=-1),
                                  lambda: either_rate([], 10)])
def test_bad_arguments_are_refused(call):
    with pytest.raises(ValueError):
        call()


def test_a_promised_rate_sets_a_stricter_threshold_or_says_how_many_parts_it_needs():
    rng = np.random.default_rng(3)
    good = rng.random(800)
    counted = choose_threshold(np.zeros(800), good, 0.01)  # 8 of 800 above: about 1.1 % of new good parts
    promised = choose_threshold(np.zeros(800), good, 0.01, confidence=0.95)  # 3 of 800 above: at most 1 % at 95 %
    assert (good > counted.threshold).sum() == 8 and (good > promised.threshold).sum() == 3
    assert upper_bound(3, 800) <= 0.01 < upper_bound(4, 800)
    assert "3 of 800 above" in promised.rule and "95% confidence" in promised.rule
    with pytest.raises(ValueError, match=r"200 good parts cannot promise at most 1.00% .* needs 299 or more"):
        choose_threshold(np.zeros(200), good[:200], 0.01, confidence=0.95)
