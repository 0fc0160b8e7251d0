"""The residual networks as the variation model's second look (rule 49): asked only about parts above the gate, their
finding side by side with the variation model's score at each one's own 1 % threshold; the model's decision kept,
its second look kept, the look surviving a checkpoint, and files from before it scoring as they did."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import torch
from test_residual_networks import defect_masks
from test_variation import parts  # same folder (pytest puts it on sys.path)

from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.draem.errors import ModelError
from model.draem.metrics import false_reject_threshold
from model.draem.residual import ResidualDetector
from model.draem.with_variation import add_residual, add_variation, networks_only, without_variation


def looked_detector() -> Detector:
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "fused", 32, "band"))
    det.init_weights(torch.Generator().manual_seed(0))
    det.eval()
    return add_variation(det, parts(40, 0), None, parts(30, 3), decision="variation", second_look=True)


@pytest.fixture(scope="module")
def with_look(tmp_path_factory: pytest.TempPathFactory) -> tuple[Detector, Detector, Path]:
    base = looked_detector()
    out = add_residual(base, parts(40, 0), None, parts(12, 9, defect=True), defect_masks(12), parts(30, 3),
                       members=1, steps=50, seed=0, look=True)
    path = tmp_path_factory.mktemp("look") / "look"
    save_checkpoint(path, out, threshold=0.5, threshold_rule="test")
    return base, out, path


def test_the_networks_raise_only_parts_above_the_gate_and_the_decision_and_second_look_are_kept(
        with_look: tuple[Detector, Detector, Path]) -> None:
    base, det, _ = with_look
    assert det.config.decision == "variation" and det.residual is not None and det.residual.looks
    assert base.variation is not None and det.variation is not None
    assert det.variation.second_look.references == 40  # kept (station residual used to drop it)
    assert torch.equal(det.variation.second_look.calibration, base.variation.second_look.calibration)
    x = torch.cat([parts(30, 4), parts(10, 5, defect=True)])
    before, after = base.predict(x).member_scores["variation"], det.predict(x).member_scores["variation"]
    window = base.variation.zmaps(x).maps.flatten(1).amax(1)
    gated = torch.tensor([base.variation.second_look.suspicious(float(w)) for w in window])
    assert bool(gated[30:].all()) and not bool(gated[:30].all())
    assert torch.equal(after[~gated], before[~gated])  # below the gate: as without the networks
    assert bool((after >= before).all()) and bool((after > before).any())  # they only raise, and they raised some
    assert "residual" not in det.predict(x).member_scores  # asked only above the gate, not reported for all


def test_the_look_puts_each_finding_against_its_own_threshold() -> None:
    res = ResidualDetector(4, 1)
    assert not res.looks
    rng = np.random.default_rng(0)
    logits = torch.from_numpy(rng.normal(3.0, 2.0, 200))
    variation = rng.normal(0.0, 1.0, 200) * 4.0
    res.calibrate_look(logits, variation)
    assert res.looks
    loc, spread, t, tv = (float(v) for v in res.look)
    assert t == pytest.approx(false_reject_threshold((logits.numpy() - loc) / spread, 0.01))
    assert tv == pytest.approx(false_reject_threshold(variation, 0.01))
    at_threshold = torch.tensor([loc + spread * t], dtype=torch.float64)
    assert float(res.look_score(at_threshold)[0]) == pytest.approx(tv)  # its threshold lands on the variation's
    with pytest.raises(ModelError, match="must be > 0"):
        res.calibrate_look(torch.zeros(200, dtype=torch.float64), variation)


def test_the_look_survives_a_checkpoint_and_a_file_from_before_it_does_not_look(
        with_look: tuple[Detector, Detector, Path], tmp_path: Path) -> None:
    _, det, path = with_look
    x = torch.cat([parts(6, 4), parts(6, 5, defect=True)])
    loaded = load_checkpoint(path).detector
    assert loaded.residual is not None and torch.equal(loaded.residual.look, det.residual.look)
    assert torch.equal(loaded.predict(x).score, det.predict(x).score)
    old = tmp_path / "old"
    save_checkpoint(old, det, threshold=0.5, threshold_rule="test")
    state = torch.load(old.with_suffix(".pt"), weights_only=True)
    del state["residual.look"]
    torch.save(state, old.with_suffix(".pt"))
    before = load_checkpoint(old, verify_hash=False).detector
    assert before.residual is not None and not before.residual.looks
    assert "residual" in before.predict(x).member_scores  # the networks report, as they did, and do not raise
    assert before.variation is not None and det.variation is not None
    assert torch.equal(before.predict(x).member_scores["variation"], det.variation.zmaps(x).scores)


def test_a_frame_of_nan_or_inf_scores_finite_and_high_with_the_look(
        with_look: tuple[Detector, Detector, Path]) -> None:
    nan_and_inf_frames_score_finite_and_high(with_look[1])


def nan_and_inf_frames_score_finite_and_high(det: Detector) -> None:
    """A frame of NaN and one of Inf beside a good part: every score and map finite, both frames scored high."""
    x = parts(3, 6)
    x[0], x[1] = float("nan"), float("inf")
    out = det.predict(x)
    assert bool(torch.isfinite(out.score).all()) and bool(torch.isfinite(out.anomaly_map).all())
    assert float(out.score[:2].min()) > 0.99


def test_the_look_needs_a_model_decided_by_its_variation_model_with_its_second_look() -> None:
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "fused", 32, "band"))
    det.init_weights(torch.Generator().manual_seed(0))
    det.eval()
    without = add_variation(det, parts(40, 0), None, parts(30, 3), decision="variation", second_look=False)
    with pytest.raises(ModelError, match="second look"):
        add_residual(without, parts(40, 0), None, parts(4, 9, defect=True), defect_masks(4), parts(30, 3),
                     members=1, steps=1, look=True)


def test_adapting_recalibrates_the_look_on_the_lines_parts_or_drops_it_with_the_second_look(
        with_look: tuple[Detector, Detector, Path]) -> None:
    from model.draem.adapt import AdaptConfig, adapt

    _, det, _ = with_look
    assert det.residual is not None
    line = parts(40, 8)
    adapted, result = adapt(det, line, torch.ones(len(line), *line.shape[2:], dtype=torch.bool),
                            AdaptConfig(false_reject=0.05), progress=False)
    assert adapted.residual is not None and adapted.residual.looks
    assert not torch.equal(adapted.residual.look, det.residual.look)  # the line's own units and thresholds
    for a, b in zip(adapted.residual.parameters(), det.residual.parameters(), strict=True):
        assert torch.equal(a, b)  # the networks are kept
    assert np.isfinite(result.heldout_scores).all()
    few = parts(15, 9)  # each fold's fit has 12 parts: no second look, so no look either
    adapted, _ = adapt(det, few, torch.ones(len(few), *few.shape[2:], dtype=torch.bool), progress=False)
    assert adapted.variation is not None and adapted.variation.second_look.references == 0
    assert adapted.residual is not None and not adapted.residual.looks


def test_networks_only_drops_the_variation_model_and_its_look_and_keeps_the_networks(
        with_look: tuple[Detector, Detector, Path], tmp_path: Path) -> None:
    """The side camera's file starts from the shipped line file's networks (make-side-model.sh): a refit of a file
    with a look is refused (the look reads the fit being replaced), so the source drops both."""
    _, looked, _ = with_look
    with pytest.raises(ModelError, match="residual networks"):
        without_variation(looked)
    bare = networks_only(looked)
    cfg = bare.config
    assert (cfg.variation, cfg.residual_members, cfg.decision, bare.residual) == (False, 0, "combined", None)
    kept = bare.state_dict()
    assert kept and not any(k.startswith(("variation.", "residual.")) for k in kept)
    assert all(torch.equal(v, looked.state_dict()[k]) for k, v in kept.items())
    assert bare.normalizer.mean == looked.normalizer.mean
    save_checkpoint(tmp_path / "bare", bare)
    assert load_checkpoint(tmp_path / "bare").detector.config == cfg
