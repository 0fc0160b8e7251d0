"""The variation model's shape check (``model.draem.shape_check``, rule 70): it finds the part's straight bottom edge,
measures how far a part's edge bends, flags a bowed part the window passes, survives a checkpoint, is off in an old
file, and no input makes it NaN."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import torch

from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.draem.errors import ModelError
from model.draem.frame_checks import EDGE_BEND_LIMIT, beyond_limits
from model.draem.shape_check import ShapeCheck, edge_sag, find_edge
from model.draem.with_variation import add_shape_check, add_variation
from tests.model.test_variation import H, W, part, parts


def edge_image(bow: float, plug: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """(H, W) intensity of a bright part over a dark belt whose bottom edge lies at row 24.5, its middle ``bow`` px
    higher than its ends (a parabola; each pixel as bright as the share of it the part covers), with a plug at the
    right whose bottom lies higher; and its region (pixels at least half covered)."""
    y, x = np.mgrid[0:H, 0:W].astype(np.float32)
    u = (x - 32.0) / 22.0
    bottom = 24.5 - bow * (1 - u**2)
    body = np.clip(bottom - y + 0.5, 0.0, 1.0) * ((y > 7) & (np.abs(x - 32) <= 22))
    lug = ((y > 10) & (y < 18) & (x > 54) & (x < 62)).astype(np.float32) if plug else np.zeros_like(body)
    cover = np.maximum(body, lug)
    return (0.05 + 0.6 * cover).astype(np.float32), cover >= 0.5


def test_the_straight_bottom_edge_is_found_and_a_bow_measured() -> None:
    image, region = edge_image(0.0)
    edge = find_edge(image, region)
    assert edge is not None
    first, end, row0, slope, sign = edge
    # the body's columns 10-54 less a tenth at each end, the plug's higher bottom left out; the edge at row 24
    assert 12 <= first <= 16 and 50 <= end <= 53 and abs(slope) < 0.01 and 23.5 <= row0 <= 25.5 and sign == -1.0
    assert abs(edge_sag(image, edge)) < 0.05
    for bow in (0.5, 1.0, 2.0):  # the middle higher: + sag, about the bow over the measured columns' span
        sag = edge_sag(edge_image(bow)[0], edge)
        u_end = (end - 1 - 32) / 22.0
        assert sag == pytest.approx(bow * u_end**2, rel=0.25), bow
    assert edge_sag(edge_image(-1.0)[0], edge) < -0.5  # the ends higher: - sag
    blank = np.full((H, W), np.nan, np.float32)
    assert math.isfinite(edge_sag(blank, edge)) or math.isnan(edge_sag(blank, edge))  # no error; never Inf
    assert find_edge(image, np.zeros((H, W), bool)) is None  # no part: no edge


def test_the_check_is_off_until_fitted_and_scores_nothing_then() -> None:
    check = ShapeCheck()
    assert not check.fitted and check.finding(5.0) == 0.0 and math.isnan(check.sag(np.zeros((H, W), np.float32)))
    check.check()
    check.calibration[0] = 1.0  # partly set: refused
    with pytest.raises(ModelError, match="calibration"):
        check.check()
    image, region = edge_image(0.0)
    check.find(image, region)  # an edge without a calibration: half switched off, refused
    with pytest.raises(ModelError, match="both set or both NaN"):
        check.check()


def test_the_threshold_is_the_largest_good_validation_part_and_the_finding_scales_to_the_window() -> None:
    image, region = edge_image(0.0)
    check = ShapeCheck()
    assert check.find(image, region)
    rng = np.random.default_rng(0)
    train, val = rng.normal(0.0, 0.1, 200), rng.normal(0.0, 0.1, 100)
    check.calibrate(train, np.r_[val, np.nan], window_at_threshold=7.0)  # a NaN sag is left out
    centre, spread, threshold, window = (float(v) for v in check.calibration)
    assert check.fitted and window == 7.0
    assert threshold * spread == pytest.approx(np.abs(val - centre).max())
    worst = centre + threshold * spread  # the largest good validation part's: within, the check says nothing
    assert check.finding(worst) == 0.0 and check.finding(centre - 0.5 * threshold * spread) == 0.0
    assert check.finding(centre + 1.01 * threshold * spread) == pytest.approx(7.07)
    assert check.finding(centre - 2 * threshold * spread) == pytest.approx(14.0)
    assert check.finding(math.nan) == 0.0
    with pytest.raises(ModelError, match="seen on 5 good training parts; it needs 10"):
        ShapeCheck().calibrate(train[:5], val, 1.0)
    with pytest.raises(ModelError, match="seen on 9 good validation parts"):
        ShapeCheck().calibrate(train, val[:9], 1.0)


def test_cross_fitted_calibration_holds_each_part_out_of_the_spread_it_is_judged_against() -> None:
    """``station adapt`` has one set of good parts: each fold's z is against the other folds' median and spread."""
    rng = np.random.default_rng(1)
    sags = rng.normal(0.3, 0.1, 60)
    sags[7] = 0.9  # one good part bent further than the rest
    order = rng.permutation(60)
    splits = [(np.setdiff1d(order, order[k::3]), order[k::3]) for k in range(3)]
    check = ShapeCheck()
    check.calibrate_crossed(np.r_[sags, np.nan], splits, window_at_threshold=5.0)
    centre, spread, threshold, window = (float(v) for v in check.calibration)
    assert centre == pytest.approx(np.median(sags)) and window == 5.0
    assert spread == pytest.approx(1.4826 * np.median(np.abs(sags - centre)))  # all the parts' (the NaN left out)
    fold = next(f for f, h in splits if 7 in h)  # the bent part's z: against the folds without it
    c = np.median(sags[fold])
    assert threshold == pytest.approx(abs(0.9 - c) / (1.4826 * np.median(np.abs(sags[fold] - c))))
    with pytest.raises(ModelError, match="seen on 5 fitted good parts"):
        ShapeCheck().calibrate_crossed(sags, [(np.arange(5), np.arange(5, 60))], 1.0)


def bowed(n: int, seed: int, bow: float) -> torch.Tensor:
    """``parts`` (no play) whose bottom edge bends ``bow`` px, middle up: near it each pixel blends part and belt by
    the share of it the bent part covers."""
    x = parts(n, seed, play=0.0)
    belt = part(np.random.default_rng(seed), dy=-40.0)  # the belt alone: the part shifted out of view
    yy, xx = np.mgrid[0:H, 0:W].astype(np.float32)
    cover = np.clip(24.5 - bow * (1 - ((xx - 32.0) / 22.0) ** 2) - yy + 0.5, 0.0, 1.0)
    near = torch.from_numpy(((yy > 18) & (yy < 27)).astype(np.float32))
    c = torch.from_numpy(cover) * near + (1 - near)
    return x * c + belt * (1 - c)


@pytest.fixture(scope="module")
def checked(tmp_path_factory: pytest.TempPathFactory) -> tuple[Detector, Detector, Path]:
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "fused", 32, "band"))
    det.init_weights(torch.Generator().manual_seed(0))
    det.eval()
    good = parts(40, 0, play=0.0)
    plain = add_variation(det, good, good[:, 0] > 0.15, parts(30, 3, play=0.0), decision="variation")
    with_check = add_variation(det, good, good[:, 0] > 0.15, parts(30, 3, play=0.0), decision="variation")
    assert add_shape_check(with_check, parts(40, 0, play=0.0), parts(30, 3, play=0.0))
    path = tmp_path_factory.mktemp("shape") / "checked"
    save_checkpoint(path, with_check, threshold=0.5, threshold_rule="test")
    return plain, with_check, path


def test_a_bowed_part_is_flagged_by_the_check_and_a_good_part_keeps_the_windows_score(checked) -> None:
    plain, with_check, _ = checked
    good, bent = parts(20, 7, play=0.0), bowed(20, 7, 1.0)
    var = with_check.variation
    assert plain.variation is not None and var is not None
    window = float(var.shape.calibration[3])  # the window's score at its own 1 % point
    for x in (good, bent):  # the score is the larger of the window's and the check's finding
        findings = torch.tensor([var.shape.finding(var.edge_sag(xi)) for xi in x.numpy()], dtype=torch.float32)
        assert torch.allclose(var.zmaps(x).scores, torch.maximum(plain.variation.zmaps(x).scores, findings))
        if x is bent:
            assert float(findings.min()) > window  # every bowed part beyond the good validation parts' sags
        else:
            assert float(findings.max()) == 0.0  # good parts keep the window's score
    assert torch.isfinite(var.zmaps(torch.full_like(good[:2], float("nan"))).scores).all()


def test_each_parts_bend_is_a_frame_check_beyond_its_limit_exactly_where_the_check_finds_it(checked) -> None:
    plain, with_check, _ = checked
    x = torch.cat([parts(10, 7, play=0.0), bowed(10, 7, 1.0)])
    out = with_check.variation.zmaps(x)
    bend = out.frame_checks()["edge_bend"]
    findings = torch.tensor([with_check.variation.shape.finding(s) for s in map(with_check.variation.edge_sag,
                                                                               x.numpy())])
    assert torch.equal(bend.abs() > EDGE_BEND_LIMIT, findings > 0)  # the same rule, one place
    assert bool((bend[10:] > EDGE_BEND_LIMIT).all())  # signed as the sag: + the middle up, as these bow
    assert torch.isnan(plain.variation.zmaps(x[:2]).edge_bend).all()  # no check: no bend
    said = beyond_limits({"edge_bend": float(bend[15])})
    assert len(said) == 1 and "bottom edge bends" in said[0]
    assert beyond_limits({"edge_bend": float(bend[0]), "noise_level": 1.0, "highlight_fraction": 0.1}) == []


def test_the_check_survives_a_checkpoint_and_an_old_file_loads_without_it(checked, tmp_path: Path) -> None:
    plain, with_check, path = checked
    loaded = load_checkpoint(path).detector
    assert loaded.variation is not None and loaded.variation.shape.fitted
    bent = bowed(5, 9, 1.5)
    assert torch.equal(loaded.variation.zmaps(bent).scores, with_check.variation.zmaps(bent).scores)
    old = tmp_path / "old"
    save_checkpoint(old, plain, threshold=0.5, threshold_rule="test")
    state = torch.load(old.with_suffix(".pt"), weights_only=True)
    for key in ("variation.shape.edge", "variation.shape.calibration", *(f"variation.outline.{k}" for k in
                                                                       ("edges", "median", "centre", "spread",
                                                                        "calibration"))):
        del state[key]
    torch.save(state, old.with_suffix(".pt"))
    var = load_checkpoint(old, verify_hash=False).detector.variation
    assert not var.shape.fitted and not var.outline.fitted  # files before either check: off


def test_a_part_without_a_straight_bottom_edge_gets_no_check() -> None:
    y, x = np.mgrid[0:H, 0:W].astype(np.float32)
    diamond = np.abs(x - 32) / 28 + np.abs(y - 16) / 14 <= 1.0  # its bottom a V: no straight run of 40 %
    image = (0.05 + 0.6 * diamond).astype(np.float32)
    assert find_edge(image, diamond) is None
    check = ShapeCheck()
    assert not check.find(image, diamond) and not check.fitted
    check.check()  # off, consistently


def test_the_variation_model_scores_the_outline_checks_finding_and_reports_its_step(checked, monkeypatch) -> None:
    """``zmaps`` takes the largest of the window's score and each check's finding, and reports each part's step
    (``model.draem.outline_check``; its own tests: tests/model/test_outline_check.py)."""
    import copy

    _, with_check, _ = checked
    det = copy.deepcopy(with_check)
    var = det.variation
    x = parts(4, 7, play=0.0)
    before = var.zmaps(x)
    assert torch.isnan(before.edge_step).all() and "edge_step" in before.frame_checks()  # off: NaN
    var.outline.edges.fill_(1.0)
    var.outline.calibration.copy_(torch.tensor([1.0, 1.0, 50.0], dtype=torch.float64))  # on, window score 50
    steps = iter([0.5, 3.0, float("nan"), 1.0])
    monkeypatch.setattr(var.outline, "step", lambda intensity: next(steps))
    out = var.zmaps(x)
    assert out.edge_step[:2].tolist() == [0.5, 3.0] and math.isnan(float(out.edge_step[2]))
    assert out.scores[1] == pytest.approx(150.0)  # 3 times the window's 1 % point: above any window score here
    assert torch.equal(out.scores[[0, 2, 3]], before.scores[[0, 2, 3]])  # within the limit, NaN: the window's
