import math

import numpy as np
import pytest

from model.draem import metrics as M


def test_auroc_of_perfect_inverted_and_one_class_scorers():
    y = np.array([0, 0, 1, 1])
    assert M.auroc(y, [0.1, 0.2, 0.8, 0.9]) == 1.0
    assert M.auroc(y, [0.9, 0.8, 0.2, 0.1]) == 0.0
    assert M.auroc(y, [0.5, 0.5, 0.5, 0.5]) == 0.5
    assert math.isnan(M.auroc([0, 0], [0.1, 0.2]))


def test_aupro_perfect_inverted_and_random():
    rng = np.random.default_rng(0)
    masks = np.zeros((4, 32, 32), bool)
    masks[0, 4:8, 4:8] = True
    masks[1, 20:30, 2:5] = True
    masks[1, 1:3, 25:31] = True
    assert M.aupro(masks, masks.astype(float)) == pytest.approx(1.0)
    assert M.aupro(masks, 1.0 - masks) == pytest.approx(0.0)
    # a random scorer has PRO ~ FPR, so the normalised area up to 0.3 is ~0.15
    assert M.aupro(masks, rng.random(masks.shape)) == pytest.approx(0.15, abs=0.05)
    assert math.isnan(M.aupro(np.zeros_like(masks), rng.random(masks.shape)))


def test_aupro_weights_regions_not_pixels():
    # one large region found, one small region missed: PRO = 0.5 regardless of their areas
    masks = np.zeros((1, 40, 40), bool)
    masks[0, 0:20, 0:20] = True
    masks[0, 30:32, 30:32] = True
    scores = np.zeros((1, 40, 40))
    scores[0, 0:20, 0:20] = 1.0
    # at FPR 0 PRO jumps to 0.5, then rises linearly to 1 at FPR 1: mean over [0, 0.3] = 0.5 + 0.5 * 0.15
    assert M.aupro(masks, scores) == pytest.approx(0.575, abs=0.01)


def test_pixel_metrics_respect_the_region():
    masks = np.zeros((1, 4, 4), bool)
    masks[0, 0, 0] = True
    maps = np.zeros((1, 4, 4))
    maps[0, 0, 0], maps[0, 3, 3] = 0.9, 1.0  # a false alarm outside the object
    region = np.ones((1, 4, 4), bool)
    region[0, 3, 3] = False
    assert M.pixel_auroc(masks, maps) < 1.0
    assert M.pixel_auroc(masks, maps, region) == 1.0
    assert M.pixel_ap(masks, maps, region) == 1.0


def test_f1_max_and_threshold_with_anomalies():
    y = np.array([0, 0, 0, 1, 1])
    s = np.array([0.1, 0.2, 0.3, 0.7, 0.8])
    f1, t = M.f1_max(y, s)
    assert f1 == 1.0 and 0.3 < t <= 0.7
    ch = M.choose_threshold(y, s)
    assert ch.flagged_good_fraction == 0.0 and ch.detected_fraction == 1.0


def test_a_weak_models_threshold_keeps_to_the_false_reject_bound():
    rng = np.random.default_rng(0)
    y = np.r_[np.zeros(100), np.ones(100)].astype(int)
    s = rng.random(200)  # a chance-level scorer: F1-max flags most parts
    assert (s[y == 0] >= M.f1_max(y, s)[1]).mean() > 0.5
    ch = M.choose_threshold(y, s, max_good_flagged=0.05)
    assert ch.flagged_good_fraction <= 0.05 and "5.00%" in ch.rule


def test_the_default_rule_rejects_at_most_the_targets_one_percent_of_good_parts():
    """Issue 19's rule: at most the target rate of good validation parts rejected, and the target is 1 % (rule 56).
    The F1-max threshold of a model that separates by two SDs rejects about 10 % of the good parts."""
    rng = np.random.default_rng(1)
    y = np.r_[np.zeros(400), np.ones(200)].astype(int)
    s = 1 / (1 + np.exp(-np.r_[rng.normal(0.0, 1.0, 400), rng.normal(2.0, 1.0, 200)]))  # scores in (0, 1)
    ch = M.choose_threshold(y, s)
    assert int((s[y == 0] > ch.threshold).sum()) == 4 and "1.00%" in ch.rule


def test_threshold_on_all_good_validation_never_flags_every_part():
    s = np.linspace(0.0, 1.0, 200)
    ch = M.choose_threshold(np.zeros(200), s, max_good_flagged=0.01)
    assert ch.flagged_good_fraction <= 0.01
    assert ch.threshold > s.min()
    assert "no anomalies" in ch.rule
    tiny = M.choose_threshold(np.zeros(3), np.array([0.2, 0.2, 0.2]))
    assert tiny.flagged_good_fraction == 0.0  # a constant scorer must not reject every good part
    with pytest.raises(ValueError, match="NaN"):
        M.choose_threshold(np.zeros(2), np.array([0.1, np.nan]))


@pytest.mark.parametrize("top", [1.0, 0.99999958])
def test_no_threshold_is_chosen_that_no_part_can_exceed(top):
    """Good parts scoring 1 (a model whose calibration collapsed, e.g. adapted on a frozen camera's identical
    frames) used to give threshold 1.0: every part passed."""
    from model.draem.adapt import adapted_threshold
    from model.draem.errors import ModelError

    good = np.array([0.3] * 5 + [top] * 20)
    with pytest.raises(ModelError, match="cannot reject"):
        M.choose_threshold(np.zeros(25, int), good)
    with pytest.raises(ModelError, match="cannot reject"):
        M.choose_threshold(np.r_[np.zeros(25, int), 1], np.r_[good, 1.0])
    with pytest.raises(ModelError, match="cannot reject"):
        adapted_threshold(np.r_[np.full(11, 0.2), top], 0.05)


def test_rank_auroc_is_auroc_with_ties_and_nan_for_one_class():
    from model.draem.metrics import auroc, rank_auroc

    rng = np.random.default_rng(1)
    for _ in range(5):
        y = rng.integers(0, 2, 120)
        s = np.round(rng.normal(0, 1, 120) + y, 1)  # many ties
        assert rank_auroc(y, s) == pytest.approx(auroc(y, s), abs=1e-12)
    assert np.isnan(rank_auroc(np.zeros(5, int), np.arange(5.0)))


def test_a_strong_models_threshold_is_the_budgets_bound_not_its_stricter_f1_point():
    """A line is judged by the defects it catches at its budget of good parts rejected. Here the F1-max point lies
    above every good part (it weighs one missed defect against four rejected good parts), so it rejects none where
    the budget allows four, and misses the defect scored just under the good parts' top four, which the bound catches.
    The threshold is the bound, wherever F1-max lies (stop 96: rule 69's candidate had been set at its stricter F1
    point, docs/results/2026-12-02-lobe-fit.md)."""
    good = np.arange(400) / 800  # 0 ... 0.49875: the 1 % bound lets the top four (0.495 and up) be rejected
    bad = np.r_[np.full(100, 0.9), 0.494]  # one defect just under the good parts' top four, the rest far above
    y, s = np.r_[np.zeros(400), np.ones(101)].astype(int), np.r_[good, bad]
    t_f1 = M.f1_max(y, s)[1]
    assert (good >= t_f1).sum() == 0 and (bad >= t_f1).sum() == 100  # the F1 point: no good part, one defect missed
    ch = M.choose_threshold(y, s)
    assert int((good > ch.threshold).sum()) == 4 and ch.detected_fraction == 1.0


def test_every_threshold_rule_spends_a_budget_whose_count_is_a_whole_number_in_full():
    """0.29 x 100 is 28.999... in floating point: each rule that turns a budget into a count of good parts allowed
    above the threshold counts 29 there, not 28 (``metrics.allowed_rejects``, the one place that counts)."""
    from model.draem.adapt import adapted_threshold

    good = np.linspace(0.01, 0.5, 100)
    assert M.allowed_rejects(0.29, 100) == 29 and M.allowed_rejects(0.01, 370) == 3
    assert int((good > M.choose_threshold(np.zeros(100), good, max_good_flagged=0.29).threshold).sum()) == 29
    assert int((good > M.false_reject_threshold(good, 0.29)).sum()) == 29
    held = np.r_[np.full(70, 0.05), 0.55, np.linspace(0.6, 0.7, 29)]  # adapt's logit-normal tail lies under 0.55
    choice = adapted_threshold(held, 0.29)
    assert "empirical quantile" in choice.rule and int((held > choice.threshold).sum()) == 29
