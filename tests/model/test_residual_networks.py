"""The residual networks: trained on the variation model's left-out residuals, they mark a defect's shape above
good parts, survive a checkpoint, decide with scores in [0, 1], and reject what the variation model cannot judge."""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
import torch
from test_variation import H, W, detector_with_variation, parts  # same folder (pytest puts it on sys.path)

from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.draem.errors import ModelError
from model.draem.lens_copies import LensCopies, lensed_signed
from model.draem.residual import TOP_K, ResidualDetector, synthetic_anomaly
from model.draem.with_variation import add_residual
from model.priors.lens import view_illumination


def defect_masks(n: int) -> torch.Tensor:
    """Where ``parts(..., defect=True)`` puts its blob, before the fixture's play (within 2 px of it)."""
    y, x = np.mgrid[0:H, 0:W]
    blob = (y - H / 2) ** 2 + (x - W / 2 + 8) ** 2 < 9.0
    return torch.from_numpy(np.repeat(blob[None], n, 0))


@pytest.fixture(scope="module")
def with_residual(tmp_path_factory: pytest.TempPathFactory) -> tuple[Detector, Path]:
    tmp_path = tmp_path_factory.mktemp("residual")
    det, _ = detector_with_variation(tmp_path)
    out = add_residual(det, parts(40, 0), None, parts(12, 9, defect=True), defect_masks(12), parts(10, 3),
                       members=2, steps=50, seed=0)  # 50 steps: defects' lowest score minus good parts' highest
    # 0.70 (0.07 at 100 steps, 0.44 at 30), at half the time of 100
    path = tmp_path / "res"
    save_checkpoint(path, out, threshold=0.5, threshold_rule="test")
    return out, path


def test_residual_networks_rank_defects_above_good_parts_decide_and_survive_a_checkpoint(
        with_residual: tuple[Detector, Path]) -> None:
    det, path = with_residual
    assert det.config.decision == "residual" and det.config.residual_members == 2
    good, bad = det.predict(parts(10, 4)), det.predict(parts(10, 5, defect=True))
    assert float(bad.member_scores["residual"].min()) > float(good.member_scores["residual"].max())
    assert float(bad.score.min()) > float(good.score.max())
    assert set(good.member_scores) == {"fused", "variation", "residual"}
    for out in (good, bad):
        assert bool(((out.score >= 0) & (out.score <= 1)).all()) and bool(torch.isfinite(out.anomaly_map).all())
    assert float(good.score.median()) < 0.5 < float(bad.score.min())  # good validation parts calibrate to ~0 SD
    loaded = load_checkpoint(path).detector
    assert loaded.config.residual_members == 2
    assert torch.equal(loaded.predict(parts(10, 4)).score, good.score)


def test_frames_the_variation_model_cannot_judge_reject_whatever_the_networks_say(
        with_residual: tuple[Detector, Path]) -> None:
    det, _ = with_residual
    x = parts(4, 6)
    x[0] = 0.0
    x[1, 0] = 1.0  # saturated
    x[2] = torch.rand(x[2].shape, generator=torch.Generator().manual_seed(0))
    x[3, :, ::2] = 1.0 - x[3, :, ::2]
    out = det.predict(x)
    assert bool(torch.isfinite(out.score).all()) and bool(torch.isfinite(out.anomaly_map).all())
    assert float(out.score.min()) > 0.99  # unjudgeable: rejected far above any threshold
    assert bool(((out.frame_checks["noise_level"] > 3) | (out.frame_checks["highlight_fraction"] > 0.5)).all())


def test_a_synthetic_anomaly_stays_on_the_part_and_off_channels_that_are_not_features() -> None:
    rng = np.random.default_rng(0)
    z = rng.standard_normal((4, H, W)).astype(np.float32)
    z[1] = 0.0  # DoLP when the model does not read it
    judged = np.zeros((H, W), bool)
    judged[8:24, 10:54] = True
    z *= judged
    for _ in range(30):
        out, mask = synthetic_anomaly(rng, z, judged)
        changed = np.abs(out - z).max(0) > 0
        assert mask.any() and not (changed & ~judged).any() and not (mask.astype(bool) & ~judged).any()
        assert not out[1].any()


def test_nothing_judged_is_scored_on_the_whole_map_not_passed() -> None:
    prob = torch.zeros(2, H, W)
    prob[:, 3, 3] = 1.0  # a finding outside the judged pixels
    judged = torch.zeros(2, H, W, dtype=torch.bool)
    judged[1, 10:20, 10:20] = True
    s = ResidualDetector.member_scores(prob, judged)
    assert abs(float(s[0]) - 1.0 / TOP_K) < 1e-6 and float(s[1]) == 0.0


def test_the_residual_decision_needs_networks_and_the_variation_model() -> None:
    cfg = ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "fused", 32, "band")
    with pytest.raises(ModelError, match="residual"):
        cfg.with_(variation=True, decision="residual")
    with pytest.raises(ModelError, match="residual_members"):
        cfg.with_(residual_members=2)
    det, _ = Detector(cfg), None
    with pytest.raises(ModelError, match="variation model"):
        add_residual(det, parts(10, 0), None, parts(2, 1, defect=True), defect_masks(2), parts(4, 3))


def test_adapting_keeps_the_residual_decision_and_recalibrates_it_on_the_lines_good_parts(
        with_residual: tuple[Detector, Path]) -> None:
    from model.draem.adapt import AdaptConfig, adapt

    det, _ = with_residual
    line = parts(30, 11) * torch.tensor([0.7, 1.0, 1.0, 1.0]).view(1, 4, 1, 1)  # a darker line
    adapted, result = adapt(det, line, line[:, 0] > 0.15, AdaptConfig(), progress=False)
    assert adapted.config.decision == "residual" and not result.decision_changed
    assert adapted.residual is not None and det.residual is not None
    assert not torch.equal(adapted.residual.calibration, det.residual.calibration)
    good = adapted.predict(parts(10, 12) * torch.tensor([0.7, 1.0, 1.0, 1.0]).view(1, 4, 1, 1)).score
    bad = adapted.predict(parts(10, 13, defect=True) * torch.tensor([0.7, 1.0, 1.0, 1.0]).view(1, 4, 1, 1)).score
    assert float((good > result.threshold.threshold).float().mean()) <= 0.2
    assert float((bad > result.threshold.threshold).float().mean()) >= 0.8


def member_inputs(n: int, seed: int) -> np.ndarray:
    """(n, 6, H, W) network inputs: four signed z channels, the part region and a spread channel."""
    rng = np.random.default_rng(seed)
    x = rng.standard_normal((n, 6, H, W)).astype(np.float32)
    x[:, 4] = 0.0
    x[:, 4, 4:H - 4, 6:W - 6] = 1.0
    return x


def test_a_member_trained_with_a_seed_is_the_same_network_whatever_the_process_drew_before() -> None:
    """The member's start comes from its seed, not from the global generator at its construction (test_residual_look
    once trained a look that raised no score only after other tests had drawn from it), and training leaves the
    global generator as it found it."""
    import model.draem.residual as residual

    good, defects = member_inputs(8, 0), member_inputs(3, 1)
    masks = np.zeros((3, H, W), bool)
    masks[:, 10:14, 20:26] = True
    nets = []
    for drawn in (1, 2):
        torch.manual_seed(drawn)
        net = residual.ResidualNet(6)
        before = torch.get_rng_state()
        residual.train_member(net, good, defects, masks, steps=3, seed=3, batch=4)
        assert torch.equal(torch.get_rng_state(), before)
        nets.append(net)
    for a, b in zip(nets[0].state_dict().values(), nets[1].state_dict().values(), strict=True):
        assert torch.equal(a, b)


def test_an_interrupted_member_resumes_from_its_state_to_the_weights_of_an_uninterrupted_run(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import model.draem.residual as residual

    good, defects = member_inputs(8, 0), member_inputs(3, 1)
    masks = np.zeros((3, H, W), bool)
    masks[:, 10:14, 20:26] = True

    def member() -> residual.ResidualNet:  # its start is train_member's (seeded_init), whatever it was built with
        return residual.ResidualNet(6)

    whole = member()
    residual.train_member(whole, good, defects, masks, steps=12, seed=3, batch=4)

    state = tmp_path / "member-0.pt"
    calls, real_loss = [0], residual.training_loss

    def killed_at_step_8(*args: torch.Tensor) -> torch.Tensor:
        calls[0] += 1
        if calls[0] == 8:
            raise KeyboardInterrupt  # the session ends mid-training
        return real_loss(*args)

    monkeypatch.setattr(residual, "training_loss", killed_at_step_8)
    with pytest.raises(KeyboardInterrupt):
        residual.train_member(member(), good, defects, masks, steps=12, seed=3, batch=4, state=state, every=5)
    monkeypatch.setattr(residual, "training_loss", real_loss)
    assert state.is_file()

    resumed = member()
    torch.manual_seed(99)  # whatever the global generator did in between
    residual.train_member(resumed, good, defects, masks, steps=12, seed=3, batch=4, state=state, every=5)
    for a, b in zip(whole.state_dict().values(), resumed.state_dict().values(), strict=True):
        assert torch.equal(a, b)

    with pytest.raises(ModelError, match=r"member-0\.pt.*another training"):
        residual.train_member(member(), good, defects, masks, steps=20, seed=3, batch=4, state=state)
    state.write_bytes(b"not a state")
    with pytest.raises(ModelError, match=r"member-0\.pt: cannot resume"):
        residual.train_member(member(), good, defects, masks, steps=12, seed=3, batch=4, state=state)


def lensed(x: torch.Tensor, vignetting: float) -> torch.Tensor:
    """Parts ``x`` (the fixture's intensity in channel 0) through a lens whose frame is the view."""
    out = x.clone()
    out[:, 0] *= torch.from_numpy(view_illumination((H, W), (0, 0, H, W), (H, W), vignetting))
    return out


def test_lens_copies_teach_the_networks_a_lens_is_no_defect(tmp_path: Path) -> None:
    """Trained as the fixture's, but with a lens copy of each good part (30 % of the light lost at the corners): good
    parts seen through such a lens score far lower than with networks never shown one (the toy: median 107 robust SD
    without, 20 with), and every defective part, lensed or not, still above every lensed good part. Copies drawn
    with no fall are the good parts themselves."""
    det, _ = detector_with_variation(tmp_path)
    var = det.variation
    assert var is not None
    good = parts(40, 0)
    signed = torch.from_numpy(copy.deepcopy(var).fit(good, None))
    none = LensCopies((0.0, 0.0), (H, W), (0, 0, H, W))
    assert torch.equal(lensed_signed(var, good, signed, none), signed)
    lens = LensCopies((0.0, 0.4), (H, W), (0, 0, H, W))
    found = {}
    for name, copies in (("plain", None), ("lens", lens)):
        out = add_residual(det, good, None, parts(12, 9, defect=True), defect_masks(12), parts(10, 3), members=1,
                           steps=50, seed=0, lens=copies)
        found[name] = [out.predict(x).member_scores["residual"] for x in
                       (lensed(parts(10, 4), 0.3), parts(10, 5, defect=True), lensed(parts(10, 5, defect=True), 0.3))]
    assert float(found["lens"][0].median()) < 0.5 * float(found["plain"][0].median())
    assert min(float(found["lens"][1].min()), float(found["lens"][2].min())) > float(found["lens"][0].max())
    with pytest.raises(ModelError, match="vignetting"):
        LensCopies((0.2, 1.0), (H, W), (0, 0, H, W))
