"""``DraemDetector`` on part of a model: a subset of an ensemble's members (the pipeline benchmark's prior sets),
and a model that sees the whole frame (roi "frame", the region of interest switched off)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import torch

from model.draem.checkpoint import save_checkpoint
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.draem.errors import ModelError
from model.draem.preprocess import crop_resize, stack_priors
from model.draem.roi import roi_box
from model.priors.api import priors_from_stokes
from model.priors.testing import detailed_stokes
from station.model_detector import DraemDetector, ModelLoadError

NAMES = ("intensity", "dolp", "aolp_cos", "aolp_sin")


def frames(n: int) -> list[dict[str, np.ndarray]]:
    """n noisy 64 x 64 frames' prior maps, computed as the station computes them."""
    rng = np.random.default_rng(0)
    s0, s1, s2 = detailed_stokes(64, 64)
    return [dict(priors_from_stokes(NAMES, s0 * rng.uniform(0.5, 1.0, s0.shape), s1, s2)) for _ in range(n)]


def save(path: Path, priors: tuple[str, ...], fusion: str, roi: str = "center", size: int = 32) -> Path:
    det = Detector(ModelConfig.from_preset("tiny", priors, fusion, size, roi))
    det.init_weights(torch.Generator().manual_seed(0))
    save_checkpoint(path, det, threshold=0.5, threshold_rule="test")
    return path


def test_a_subset_of_members_reads_only_its_priors_and_scores_as_those_members(tmp_path: Path) -> None:
    path = save(tmp_path / "ens", ("intensity", "dolp", "aolp"), "ensemble")
    maps = frames(2)
    sub = DraemDetector(path, "cpu", members=("intensity", "aolp"))
    assert sub.priors == ("intensity", "aolp_cos", "aolp_sin") and sub.used_priors == ("intensity", "aolp")
    # the same two members run by the full model on the full stack give the same score: the zeros in the left-out
    # member's channels are never read
    full = DraemDetector(path, "cpu")
    for m in maps:
        x = stack_priors(m, full.config.priors)
        top, left, h, w = roi_box("center", x.shape[1:])
        xt, _ = crop_resize(x[:, top:top + h, left:left + w], (0, 0, h, w), 32, full.config.priors)
        ref = full.net.predict(xt[None], members=("intensity", "aolp"))
        only = {k: m[k] for k in sub.priors}  # what the inspector computes for this detector
        assert sub.infer(only).score == pytest.approx(float(ref.score[0]), abs=1e-6)
    assert sub.members_run == 2 * 2
    with pytest.raises(ModelLoadError, match="normal"):
        DraemDetector(path, "cpu", members=("normal",))
    with pytest.raises(ModelLoadError, match="fused model"):
        DraemDetector(save(tmp_path / "fused", ("intensity", "dolp"), "fused"), "cpu", members=("intensity",))


def test_roi_frame_sees_the_whole_frame_and_center_only_its_square(tmp_path: Path) -> None:
    wide = {k: np.concatenate([v, v[:, :32]], 1) for k, v in frames(1)[0].items()}  # 64 x 96: wider than tall
    heat = {roi: DraemDetector(save(tmp_path / roi, ("intensity", "dolp", "aolp"), "fused", roi), "cpu")
            .infer(wide).heatmap for roi in ("center", "frame")}
    assert roi_box("frame", (64, 96)) == (0, 0, 64, 96) and roi_box("center", (64, 96)) == (0, 16, 64, 64)
    assert not heat["center"][:, :16].any() and not heat["center"][:, 80:].any()
    assert heat["frame"][:, :16].any() and heat["frame"][:, 80:].any()
    with pytest.raises(ModelError, match="centre square"):
        ModelConfig.from_preset("tiny", ("intensity", "normal"), "fused", 32, "frame")


def test_roi_band_sees_the_middle_half_of_the_centre_square_at_twice_its_resolution(tmp_path: Path) -> None:
    wide = {k: np.concatenate([v, v[:, :32]], 1) for k, v in frames(1)[0].items()}  # 64 x 96
    assert roi_box("band", (64, 96)) == (16, 16, 32, 64) and roi_box("band", (480, 640)) == (120, 80, 240, 480)
    det = DraemDetector(save(tmp_path / "band", ("intensity", "dolp", "aolp"), "fused", "band"), "cpu")
    assert det.config.input_shape == (32, 64)  # the centre square's 64 x 64 would be 32 x 32
    heat = det.infer(wide).heatmap
    assert heat.shape == (64, 96) and heat[16:48, 16:80].all()
    assert not heat[:16].any() and not heat[48:].any() and not heat[:, :16].any() and not heat[:, 80:].any()
    # the band lies inside the centre square the normal estimator reads, so it takes the normal prior (cut from the
    # square: tests/station/test_normal_prior.py); the whole frame does not (above)
    assert ModelConfig.from_preset("tiny", ("intensity", "normal"), "fused", 32, "band").roi == "band"


def test_roi_tall_sees_the_middle_two_thirds_of_the_centre_square_at_the_bands_detail(tmp_path: Path) -> None:
    """"tall": room above and below the band's part (a camera turned a few degrees keeps the part's ends in view,
    docs/results/2026-12-05-seen-edges.md) at the band's detail: 320 x 480 frame px at 128 x 192 as 240 x 480 at
    96 x 192."""
    wide = {k: np.concatenate([v, v[:, :32]], 1) for k, v in frames(1)[0].items()}  # 64 x 96
    assert roi_box("tall", (480, 640)) == (80, 80, 320, 480) and roi_box("tall", (64, 96)) == (10, 16, 42, 64)
    assert roi_box("tall", (2048, 2448), frame_aspect=4 / 3) == (412, 306, 1224, 1836)
    assert ModelConfig.from_preset("tiny", ("intensity",), "fused", 128, "tall").input_shape == (128, 192)
    with pytest.raises(ModelError, match="multiple of 32"):
        ModelConfig.from_preset("tiny", ("intensity",), "fused", 96, "tall")  # 144 columns
    det = DraemDetector(save(tmp_path / "tall", ("intensity", "dolp", "aolp"), "fused", "tall", size=64), "cpu")
    assert det.config.input_shape == (64, 96)
    heat = det.infer(wide).heatmap
    assert heat.shape == (64, 96) and heat[10:52, 16:80].all()
    assert not heat[:10].any() and not heat[52:].any() and not heat[:, :16].any() and not heat[:, 80:].any()


def test_the_region_keeps_to_the_training_frames_view_on_a_taller_frame() -> None:
    """A model trained on 4:3 frames (frame_aspect 4/3) sees the same part of the view on the whole 2448 x 2048
    sensor; a model that records no aspect, or was trained on square frames (an imported MVTec set), keeps the
    frame's own square, as before."""
    from model.draem.checkpoint import load_checkpoint

    assert roi_box("band", (480, 640), frame_aspect=4 / 3) == roi_box("band", (480, 640)) == (120, 80, 240, 480)
    assert roi_box("band", (2048, 2448), frame_aspect=4 / 3) == (564, 306, 918, 1836)
    assert roi_box("center", (2048, 2448), frame_aspect=4 / 3) == (106, 306, 1836, 1836)
    assert roi_box("center", (2048, 2448)) == roi_box("center", (2048, 2448), frame_aspect=1.0) == (0, 200, 2048, 2048)
    assert roi_box("center", (64, 64), frame_aspect=1.0) == (0, 0, 64, 64)
    assert roi_box("center", (64, 96), frame_aspect=4 / 3) == (0, 16, 64, 64)  # wider than trained: as before
    assert load_checkpoint("model/weights/default").detector.config.frame_aspect == pytest.approx(4 / 3)
    with pytest.raises(ModelError, match="frame_aspect"):
        ModelConfig.from_preset("tiny", ("intensity",), "fused", 32).with_(frame_aspect=float("nan"))
