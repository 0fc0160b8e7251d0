"""The variation model's outline check (``model.draem.outline_check``): it finds the part's two long edges, flags a
short step along either (flash) beyond every good part's, leaves a bend to the shape check, is off until fitted,
says so in a reason, and no input makes it Inf."""

from __future__ import annotations

import logging
import math

import numpy as np
import pytest
import torch

from model.draem.adapt import _refit_outline
from model.draem.errors import ModelError
from model.draem.frame_checks import EDGE_STEP_LIMIT, beyond_limits
from model.draem.outline_check import MARGIN_PX, OutlineCheck, find_edges

H, W = 80, 128
TOP, BOTTOM, LEFT, RIGHT = 30.0, 62.0, 8, 120


def image(rng: np.random.Generator, top_step: float = 0.0, bottom_step: float = 0.0, bend: float = 0.0,
          at: tuple[int, int] = (50, 70)) -> np.ndarray:
    """(H, W) intensity of a part seen from above and in front: a bright top face over a grey front face whose top edge
    lies at row TOP and bottom edge at row BOTTOM over a dark belt, columns LEFT-RIGHT, each edge moved by a part's
    jitter (+-0.15 px), by a step of ``top_step`` / ``bottom_step`` rows down over the columns ``at`` (a fin) and
    bent ``bend`` px up in the middle (a bow); each pixel as bright as the shares of it each face covers, plus noise."""
    y, x = np.mgrid[0:H, 0:W].astype(np.float64)
    u = (x - (LEFT + RIGHT) / 2) / ((RIGHT - LEFT) / 2)
    fin = (x >= at[0]) & (x < at[1])
    top = TOP + rng.normal(0, 0.15) - bend * (1 - u**2) + top_step * fin
    bottom = BOTTOM + rng.normal(0, 0.15) - bend * (1 - u**2) + bottom_step * fin
    above_top = np.clip(top - y + 0.5, 0, 1)
    above_bottom = np.clip(bottom - y + 0.5, 0, 1)
    inside = (x >= LEFT) & (x <= RIGHT) & (y >= 8)
    value = np.where(inside, 0.8 * above_top + 0.4 * (above_bottom - above_top) + 0.05 * (1 - above_bottom), 0.05)
    return (value + rng.normal(0, 0.04, value.shape)).astype(np.float32)


def region() -> np.ndarray:
    y, x = np.mgrid[0:H, 0:W]
    return (x >= LEFT) & (x <= RIGHT) & (y >= 8) & (y <= BOTTOM)


@pytest.fixture(scope="module")
def fitted() -> OutlineCheck:
    rng = np.random.default_rng(0)
    check = OutlineCheck(W)
    assert check.find(image(rng), region())
    train = np.stack([check.deviations(image(rng)) for _ in range(60)])
    val = np.stack([check.deviations(image(rng)) for _ in range(40)])
    check.calibrate(train, val, window_at_threshold=7.0)
    check.check()
    return check


def test_both_long_edges_are_found_along_the_straight_run_less_its_margins() -> None:
    edges = find_edges(image(np.random.default_rng(1)), region())
    assert edges is not None
    (first, end, bottom_row, bottom_slope, bottom_sign), (_, _, top_row, top_slope, top_sign) = edges
    assert first == LEFT + MARGIN_PX and end == RIGHT + 1 - MARGIN_PX
    assert abs(bottom_row - BOTTOM) <= 1.0 and abs(top_row - TOP) <= 1.0 and abs(bottom_slope) + abs(top_slope) < 0.01
    assert bottom_sign == -1.0 and top_sign == -1.0  # both: brighter above than below
    assert find_edges(image(np.random.default_rng(1)), np.zeros((H, W), bool)) is None  # no part: no edges


def test_a_fin_at_either_edge_steps_beyond_every_good_part_and_the_finding_scales_to_the_window(fitted) -> None:
    rng = np.random.default_rng(2)
    good = [fitted.step(image(rng)) for _ in range(40)]
    assert max(good) <= 1.3 and fitted.finding(float(np.median(good))) == 0.0  # good parts: within or near
    for kw in ({"top_step": 1.5}, {"bottom_step": 1.5}, {"top_step": -1.0, "at": (30, 45)}):
        step = fitted.step(image(rng, **kw))
        assert step > 2 * EDGE_STEP_LIMIT, kw  # a short step of a row or more over 15-20 columns: far beyond
        assert fitted.finding(step) == pytest.approx(7.0 * step)
    said = beyond_limits({"edge_step": 2.5})
    assert len(said) == 1 and "an edge steps 2.5 times" in said[0]
    assert beyond_limits({"edge_step": EDGE_STEP_LIMIT}) == []  # at the limit: within it


def test_a_bend_is_left_to_the_shape_check(fitted) -> None:
    """Each part's own parabola is taken out: a bowed part's edges are smooth, and the outline check stays quiet (with
    the pixel noise of these images; without any, the sub-pixel rows' own ripple as a bend sweeps them reads as a few
    robust SD: measured 2.7-3.2 at a 1.5 px bend and noise 0.005)."""
    rng = np.random.default_rng(3)
    assert all(fitted.step(image(rng, bend=1.5)) <= 1.3 for _ in range(5))


def test_the_check_is_off_until_fitted_and_refuses_a_half_set_file() -> None:
    check = OutlineCheck(W)
    assert not check.fitted and math.isnan(check.step(image(np.random.default_rng(4)))) and check.finding(5.0) == 0.0
    check.check()
    assert check.find(image(np.random.default_rng(4)), region())  # edges without a calibration: refused
    with pytest.raises(ModelError, match="both set or both NaN"):
        check.check()
    check.clear()
    check.check()
    with pytest.raises(ModelError, match="seen on 5 good training parts; it needs 10"):
        OutlineCheck(W).calibrate(np.full((5, 2, W), 0.0), np.zeros((20, 2, W)), 1.0)


def test_no_input_makes_it_inf_and_a_blank_frame_fails_no_one(fitted) -> None:
    for x in (np.full((H, W), np.nan, np.float32), np.full((H, W), np.inf, np.float32), np.zeros((H, W), np.float32),
              np.full((H, W), 1e30, np.float32)):
        step = fitted.step(x)
        assert not math.isinf(step) and math.isfinite(fitted.finding(step))


def test_cross_fitted_thresholds_hold_each_part_out_of_the_statistics_it_is_judged_against() -> None:
    rng = np.random.default_rng(5)
    check = OutlineCheck(W)
    assert check.find(image(rng), region())
    d = np.stack([check.deviations(image(rng, top_step=1.0 if i == 7 else 0.0)) for i in range(45)])
    splits = [(np.setdiff1d(np.arange(45), np.arange(k, 45, 3)), np.arange(k, 45, 3)) for k in range(3)]
    check.calibrate_crossed(d, splits, window_at_threshold=5.0)
    bottom, top, window = (float(v) for v in check.calibration)
    assert window == 5.0 and top > 2 * bottom  # the stepped part, held out, set the top edge's threshold


class Registered:
    """What ``station adapt``'s refit reads of a variation model: its reference, region and outline check, and each
    frame's registered intensity (here the frame itself)."""

    def __init__(self) -> None:
        self.reference = torch.from_numpy(image(np.random.default_rng(6)))
        self.region = torch.from_numpy(region())
        self.outline = OutlineCheck(W)

    def outline_deviations(self, xi: np.ndarray, around: np.ndarray | None = None) -> np.ndarray:
        return self.outline.deviations(xi[0])


def test_adapt_refits_the_outline_check_on_the_lines_parts_or_switches_it_off_and_says_why(caplog) -> None:
    rng = np.random.default_rng(7)
    x = torch.from_numpy(np.stack([image(rng) for _ in range(30)])[:, None])
    splits = [(np.setdiff1d(np.arange(30), np.arange(k, 30, 3)), np.arange(k, 30, 3)) for k in range(3)]
    var = Registered()
    said = _refit_outline(var, x, splits, window=4.0)
    assert said.startswith("outline check refitted: thresholds z") and var.outline.fitted
    assert float(var.outline.calibration[2]) == 4.0
    few = Registered()
    with caplog.at_level(logging.WARNING):
        said = _refit_outline(few, x[:12], [(np.arange(6), np.arange(6, 12))], window=4.0)
    assert said.startswith("no outline check: outline check: the edges are seen on 6 fitted good parts")
    assert "no outline check" in caplog.text and not few.outline.fitted


def test_adapt_floors_the_refitted_thresholds_at_the_trained_models_when_asked() -> None:
    """On few parts the largest held-out z sits low in the good parts' tail (on 90 parts of seed 1196 the bottom
    edge's 6.28 against the trained file's 8.7, and two of four good parts rejected were this check's): with a floor
    each edge's threshold is no lower than the trained model's, and the summary says whose it is."""
    rng = np.random.default_rng(7)
    x = torch.from_numpy(np.stack([image(rng) for _ in range(30)])[:, None])
    splits = [(np.setdiff1d(np.arange(30), np.arange(k, 30, 3)), np.arange(k, 30, 3)) for k in range(3)]
    alone = Registered()
    _refit_outline(alone, x, splits, window=4.0)
    refit = alone.outline.calibration[:2].clone()
    trained = Registered()
    trained.outline.calibration.copy_(torch.tensor([float(refit[0]) + 3.0, float(refit[1]) - 0.5, 9.0],
                                                   dtype=torch.float64))
    floored = Registered()
    said = _refit_outline(floored, x, splits, window=4.0, floor=trained)
    bottom, top, window = (float(v) for v in floored.outline.calibration)
    assert bottom == float(refit[0]) + 3.0 and top == float(refit[1]) and window == 4.0
    assert f"z {bottom:.2f} (the trained model's; the largest held-out part's {float(refit[0]):.2f})" in said
    assert f"z {top:.2f} (the largest held-out part's) at the top edge" in said


def test_no_step_is_read_from_pixels_the_registration_made_up(fitted) -> None:
    """On a turned camera the warp turning a frame back reaches below the input and replicates its border: the belt
    under the part's left end becomes stripes, and the bottom edge read there stepped up to 76 robust SD on good parts
    of seed 1203 (docs/results/2026-12-05-seen-edges.md). Marked unseen (NaN), those columns are not read."""
    rng = np.random.default_rng(8)
    cols = slice(LEFT + MARGIN_PX, LEFT + MARGIN_PX + 24)
    made_up = image(rng)
    made_up[int(BOTTOM) - 2:, cols] = made_up[int(BOTTOM) - 3, cols]  # the row above the edge, replicated down
    assert fitted.step(made_up) > 2 * EDGE_STEP_LIMIT  # read as it was: a step beyond every good part's
    marked = made_up.copy()
    marked[int(BOTTOM) - 2:, cols] = np.nan
    d = fitted.deviations(marked)
    assert np.isnan(d[0, cols]).all() and np.isfinite(d[0, cols.stop + 4:RIGHT - MARGIN_PX]).all()
    assert np.isfinite(d[1, cols]).all()  # the top edge, seen there, is read
    assert fitted.step(marked) <= 1.3 and fitted.finding(fitted.step(marked)) == 0.0
