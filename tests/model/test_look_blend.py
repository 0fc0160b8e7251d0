"""The look network's blend (``model.draem.residual``, ``BLEND``): the network asked about every part, a part scoring,
in the window's units, its window threshold times the larger of the weighted sum of the window's and the network's
findings each over its own 1 % threshold on good validation parts, and the checks' part over the window's threshold;
weight 0 the cascade, as files before it load; the thresholds surviving a checkpoint and set again by adapting."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import torch
from test_residual_look import (  # noqa: F401  (with_look: the fixture, a detector whose networks are its look)
    nan_and_inf_frames_score_finite_and_high,
    with_look,
)
from test_variation import parts  # same folder (pytest puts it on sys.path)

from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.detector import Detector
from model.draem.errors import ModelError
from model.draem.metrics import false_reject_threshold
from model.draem.residual import BLEND_WEIGHT, NO_BLEND, ResidualDetector, blended
from model.draem.with_variation import add_blend, blend_inputs


def test_the_blend_weighs_each_finding_over_its_threshold_and_a_check_keeps_its_part() -> None:
    score = torch.tensor([2.0, 8.0, 30.0, 1.0], dtype=torch.float64)  # the window with its checks
    window = torch.tensor([2.0, 8.0, 4.0, 1.0], dtype=torch.float64)  # part 2: a check lifted it to 30
    found = torch.tensor([1.0, 1.0, 1.0, 9.0], dtype=torch.float64)
    out = blended(score, window, found, weight=0.25, window_threshold=10.0, finding_threshold=3.0)
    want = [10 * max(0.25 * s / 10 + 0.75 * f / 3, (s if s > w + 1e-4 else 0.0) / 10)
            for s, w, f in zip(score.tolist(), window.tolist(), found.tolist(), strict=True)]
    assert out.tolist() == pytest.approx(want)
    assert float(out[2]) == 30.0  # the check's finding is kept whole
    assert float(out[3]) > 10.0 > float(out[1])  # the network alone rejects; a window near its threshold alone not
    assert blended(score, window, found, 1.0, 10.0, 3.0).tolist() == pytest.approx(score.tolist())  # weight 1


def test_calibrating_the_blend_takes_each_findings_1_percent_threshold_and_refuses_nonsense() -> None:
    res = ResidualDetector(4, 1)
    assert not res.blends and tuple(res.blend.tolist()) == NO_BLEND
    rng = np.random.default_rng(0)
    w, f = rng.normal(5.0, 2.0, 300), rng.normal(3.0, 1.0, 300)
    with pytest.raises(ModelError, match="look"):  # no look to blend
        res.calibrate_blend(0.25, w, f)
    res.look.copy_(torch.tensor([0.0, 1.0, 2.0, 3.0], dtype=torch.float64))
    res.calibrate_blend(0.25, w, f)
    assert res.blends
    assert res.blend.tolist() == pytest.approx([0.25, false_reject_threshold(w, 0.01), false_reject_threshold(f, 0.01)])
    for weight in (0.0, -0.1, 1.5, float("nan")):
        with pytest.raises(ModelError, match="weight"):
            res.calibrate_blend(weight, w, f)
    with pytest.raises(ModelError, match="> 0"):
        res.calibrate_blend(0.25, w - 100.0, f)
    res.blend.copy_(torch.tensor([0.25, float("nan"), 1.0], dtype=torch.float64))
    with pytest.raises(ModelError, match="blend"):
        res.check()


def test_a_blended_detector_asks_the_network_about_every_part_and_scores_by_the_rule(
        with_look: tuple[Detector, Detector, Path]) -> None:  # noqa: F811
    _, det, _ = with_look
    val_good = parts(30, 3)
    blend = add_blend(det, val_good, 0.25)
    assert det.residual is not None and not det.residual.blends  # a copy: the cascade is left as it was
    assert blend.residual is not None and blend.residual.blends
    w_val, f_val = blend_inputs(det, val_good)
    weight, t_w, t_f = blend.residual.blend.tolist()
    assert (weight, t_w, t_f) == pytest.approx((0.25, false_reject_threshold(w_val, 0.01),
                                                false_reject_threshold(f_val, 0.01)))
    x = torch.cat([parts(20, 4), parts(10, 5, defect=True)])
    v = det.variation.zmaps(x, signed=True)
    w, f = blend_inputs(det, x)
    checks = np.where(w > v.maps.flatten(1).amax(1).double().numpy() + 1e-4, w, 0.0)
    want = t_w * np.maximum(0.25 * w / t_w + 0.75 * f / t_f, checks / t_w)
    got = blend.predict(x).member_scores["variation"].double().numpy()
    assert got == pytest.approx(want, rel=1e-5)
    cascade = det.predict(x).member_scores["variation"].double().numpy()
    assert not np.allclose(got, cascade)  # parts below the gate are asked too


def test_a_blended_detector_reports_each_parts_look_level_and_the_cascade_none(
        with_look: tuple[Detector, Detector, Path]) -> None:  # noqa: F811
    """``look_level``, a frame check: the network's finding over its blend threshold (f / t_f), what the station's
    look monitor reads; a file without the blend reports none."""
    _, det, _ = with_look
    blend = add_blend(det, parts(30, 3), 0.25)
    x = torch.cat([parts(8, 4), parts(4, 5, defect=True)])
    _, f = blend_inputs(det, x)
    checks = blend.predict(x).frame_checks
    assert "look_level" in checks and checks["look_level"].shape == (12,)
    assert checks["look_level"].double().numpy() == pytest.approx(f / float(blend.residual.blend[2]), rel=1e-5)
    assert "look_level" not in det.predict(x).frame_checks


def test_the_blend_survives_a_checkpoint_and_a_file_from_before_it_scores_by_the_cascade(
        with_look: tuple[Detector, Detector, Path], tmp_path: Path) -> None:  # noqa: F811
    _, det, _ = with_look
    blend = add_blend(det, parts(30, 3), 0.25)
    x = torch.cat([parts(6, 4), parts(6, 5, defect=True)])
    save_checkpoint(tmp_path / "blend", blend, threshold=0.5, threshold_rule="test")
    loaded = load_checkpoint(tmp_path / "blend").detector
    assert loaded.residual is not None and torch.equal(loaded.residual.blend, blend.residual.blend)
    assert torch.equal(loaded.predict(x).score, blend.predict(x).score)
    state = torch.load((tmp_path / "blend").with_suffix(".pt"), weights_only=True)
    del state["residual.blend"]
    torch.save(state, (tmp_path / "blend").with_suffix(".pt"))
    before = load_checkpoint(tmp_path / "blend", verify_hash=False).detector
    assert before.residual is not None and not before.residual.blends
    assert torch.equal(before.predict(x).score, det.predict(x).score)


def test_a_frame_of_nan_or_inf_scores_finite_and_high_with_the_blend(
        with_look: tuple[Detector, Detector, Path]) -> None:  # noqa: F811
    _, det, _ = with_look
    nan_and_inf_frames_score_finite_and_high(add_blend(det, parts(30, 3), 0.25))


def test_a_blend_needs_the_networks_as_a_look() -> None:
    from test_residual_look import looked_detector

    with pytest.raises(ModelError, match="look"):
        add_blend(looked_detector(), parts(30, 3), 0.25)


def test_adapting_sets_the_blends_thresholds_on_the_lines_parts(
        with_look: tuple[Detector, Detector, Path]) -> None:  # noqa: F811
    from model.draem.adapt import AdaptConfig, adapt

    _, det, _ = with_look
    blend = add_blend(det, parts(30, 3), 0.25)
    line = parts(40, 8)
    adapted, result = adapt(blend, line, torch.ones(len(line), *line.shape[2:], dtype=torch.bool),
                            AdaptConfig(false_reject=0.05), progress=False)
    assert adapted.residual is not None and adapted.residual.blends
    assert float(adapted.residual.blend[0]) == 0.25  # the weight is the recipe's
    assert not torch.equal(adapted.residual.blend, blend.residual.blend)  # the thresholds the line's own
    assert np.isfinite(result.heldout_scores).all()
    few = parts(15, 9)  # no second look, so no look, so no blend
    adapted, _ = adapt(blend, few, torch.ones(len(few), *few.shape[2:], dtype=torch.bool), progress=False)
    assert adapted.residual is not None and not adapted.residual.looks and not adapted.residual.blends


def test_the_shipped_file_decides_by_the_blend() -> None:
    """model/weights/default is the recipe make model makes: its look blended at BLEND_WEIGHT, both thresholds set."""
    residual = load_checkpoint("model/weights/default").detector.residual
    assert residual is not None and residual.blends
    weight, t_w, t_f = (float(v) for v in residual.blend)
    assert weight == BLEND_WEIGHT and np.isfinite([t_w, t_f]).all() and t_w > 0 and t_f > 0
