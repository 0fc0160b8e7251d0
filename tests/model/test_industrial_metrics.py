"""Industrial metrics (parts caught at a fixed false-reject rate, per defect type) and the holdout helper."""

import math

import numpy as np
import pytest

from model.draem import metrics as M
from model.draem.holdout import indices_without_type


def test_threshold_rejects_at_most_the_rate_of_good_parts():
    good = np.arange(100) / 100.0  # 0.00 .. 0.99
    t = M.false_reject_threshold(good, 0.05)
    assert t == 0.94 and (good > t).sum() == 5
    assert M.false_reject_threshold(good, 0.0) == 0.99  # nothing good rejected: the maximum passes
    assert (good > M.false_reject_threshold(good, 0.29)).sum() == 29  # 0.29 * 100 = 28.999... in floating point
    assert (good > M.false_reject_threshold(good, 0.019)).sum() == 1  # floor: never more than the rate
    with pytest.raises(ValueError, match=r"\[0, 1\)"):
        M.false_reject_threshold(good, 1.0)
    with pytest.raises(ValueError, match="no good parts"):
        M.false_reject_threshold(np.array([]), 0.05)


def test_caught_at_false_reject_hand_made():
    y = np.array([0, 0, 0, 0, 1, 1, 1, 1])
    s = np.array([0.1, 0.2, 0.3, 0.4, 0.35, 0.5, 0.6, 0.05])
    caught, t = M.caught_at_false_reject(y, s, 0.0)
    assert t == 0.4 and caught == 0.5  # 0.5 and 0.6 above the best good part; 0.35 and 0.05 escape
    caught, t = M.caught_at_false_reject(y, s, 0.25)  # one good part of four may be rejected
    assert t == 0.3 and caught == 0.75


def test_ties_at_the_threshold_pass_as_at_the_station():
    # three good parts tie at 0.2: allowing 2 of 5 rejects cannot split the tie, so only 0.3 is rejected
    y = np.array([0, 0, 0, 0, 0, 1, 1])
    s = np.array([0.1, 0.2, 0.2, 0.2, 0.3, 0.2, 0.25])
    caught, t = M.caught_at_false_reject(y, s, 0.4)
    assert t == 0.2
    assert (s[y == 0] > t).mean() == 0.2 <= 0.4
    assert caught == 0.5  # the defect scoring exactly the threshold passes (score > threshold rejects)


def test_no_defective_parts_all_equal_scores_and_bad_input():
    caught, t = M.caught_at_false_reject(np.zeros(4), np.array([0.1, 0.2, 0.3, 0.4]), 0.25)
    assert math.isnan(caught) and t == 0.3
    caught, t = M.caught_at_false_reject(np.array([0, 0, 1, 1]), np.full(4, 0.7), 0.05)
    assert caught == 0.0 and t == 0.7  # a constant scorer catches nothing and rejects no good part
    with pytest.raises(ValueError, match="no good parts"):
        M.caught_at_false_reject(np.ones(3), np.array([0.1, 0.2, 0.3]), 0.05)
    with pytest.raises(ValueError, match="NaN"):
        M.caught_at_false_reject(np.array([0, 1]), np.array([0.1, np.nan]), 0.05)
    with pytest.raises(ValueError, match="labels but"):
        M.caught_at_false_reject(np.array([0, 1]), np.array([0.1]), 0.05)


def test_threshold_held_fixed_from_validation():
    val_y, val_s = np.zeros(4), np.array([0.1, 0.2, 0.3, 0.9])  # a noisy good part in validation
    y, s = np.array([0, 0, 1, 1]), np.array([0.1, 0.2, 0.5, 0.95])
    assert M.caught_at_false_reject(y, s, 0.0) == (1.0, 0.2)  # threshold from the test set itself
    assert M.caught_at_false_reject(y, s, 0.0, threshold_from=(val_y, val_s)) == (0.5, 0.9)


def test_detection_by_type():
    y = np.array([0, 0, 0, 0, 1, 1, 1, 1, 1])
    s = np.array([0.1, 0.2, 0.3, 0.4, 0.9, 0.8, 0.25, 0.05, 0.45])
    types = ["", "", "", "", "dent", "dent", "scratch", "scratch", "stud"]
    r = M.detection_by_type(y, s, types, false_rejects=(0.0, 0.25))
    assert r.thresholds == {0.0: 0.4, 0.25: 0.3} and r.threshold_source == "evaluated set"
    assert r.false_reject_observed == {0.0: 0.0, 0.25: 0.25} and r.n_good == 4
    assert r.good_rejected == {0.0: 0, 0.25: 1}  # the counts behind the shares
    assert list(r.per_type) == ["dent", "scratch", "stud"]
    dent, scratch, stud = r.per_type.values()
    assert dent.n_defective == 2 and dent.image_auroc == 1.0 and dent.caught == {0.0: 1.0, 0.25: 1.0}
    assert scratch.image_auroc == pytest.approx(2 / 8)  # pairs won: 0.25 beats 0.1 and 0.2; 0.05 beats none
    assert scratch.caught == {0.0: 0.0, 0.25: 0.0}
    assert stud.caught == {0.0: 1.0, 0.25: 1.0}
    assert r.overall.defect_type == "all" and r.overall.n_defective == 5
    assert r.overall.caught == {0.0: 0.6, 0.25: 0.6}
    assert r.overall.image_auroc == pytest.approx(M.auroc(y, s))

    # thresholds from a validation set are applied unchanged; the observed false-reject rate can then exceed the rate
    v = M.detection_by_type(y, s, types, (0.0,), validation=(np.zeros(3), np.array([0.0, 0.1, 0.2])))
    assert v.thresholds == {0.0: 0.2} and v.threshold_source == "validation"
    assert v.false_reject_observed[0.0] == 0.5 and v.per_type["scratch"].caught[0.0] == 0.5

    # no defective parts: no types, NaN overall; all-equal scores: chance AUROC, nothing caught
    none = M.detection_by_type(np.zeros(3), np.array([0.1, 0.2, 0.3]), ["", "", ""])
    assert none.per_type == {} and math.isnan(none.overall.image_auroc) and math.isnan(none.overall.caught[0.01])
    flat = M.detection_by_type(y, np.full(9, 0.5), types)
    assert flat.overall.image_auroc == 0.5 and flat.overall.caught == {0.01: 0.0, 0.05: 0.0}
    with pytest.raises(ValueError, match="types for"):
        M.detection_by_type(y, s, types[:-1])


def test_parts_the_station_could_not_judge_count_as_rejected_not_as_scored():
    """A frame the station would not judge (no part in view, invalid pixels) is rejected at the line whatever the
    model would have scored it: the caught and good-rejected figures count it so, the ranking (AUROC) does not."""
    y = np.array([0, 0, 0, 0, 1, 1, 1, 1, 1])
    s = np.array([0.1, 0.2, 0.3, 0.4, 0.9, 0.8, 0.25, 0.05, 0.45])
    types = ["", "", "", "", "dent", "dent", "scratch", "scratch", "stud"]
    plain = M.detection_by_type(y, s, types, (0.0,))
    forced = M.detection_by_type(y, s, types, (0.0,), rejected=np.array([1, 0, 0, 0, 0, 0, 0, 1, 0], bool))
    assert forced.thresholds == plain.thresholds == {0.0: 0.4}
    assert plain.false_reject_observed[0.0] == 0.0 and forced.false_reject_observed[0.0] == 0.25
    assert plain.per_type["scratch"].caught[0.0] == 0.0 and forced.per_type["scratch"].caught[0.0] == 0.5
    assert forced.overall.caught[0.0] == pytest.approx(0.8) and plain.overall.caught[0.0] == pytest.approx(0.6)
    assert forced.overall.image_auroc == plain.overall.image_auroc
    with pytest.raises(ValueError, match="rejected flags for"):
        M.detection_by_type(y, s, types, rejected=np.zeros(3, bool))


def test_holdout_indices_drop_only_the_held_out_type():
    types = ["", "dent", None, "scratch", "dent", "stud", ""]
    assert indices_without_type(types, "dent").tolist() == [0, 2, 3, 5, 6]
    assert indices_without_type(types, ["dent", "stud"]).tolist() == [0, 2, 3, 6]
    assert indices_without_type(np.array(types, dtype=object), "scratch").dtype == np.int64
    with pytest.raises(ValueError, match=r"no sample of type \['dnet'\].*'dent', 'scratch', 'stud'"):
        indices_without_type(types, "dnet")
    with pytest.raises(ValueError, match="at least one"):
        indices_without_type(types, [])
