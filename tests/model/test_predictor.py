"""``model.draem.predictor.load_predictor``: the model-side loader the station's ``DraemDetector`` wraps."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import torch

from model.draem.checkpoint import save_checkpoint
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.draem.errors import ModelError
from model.draem.predictor import PRIOR_MAPS, load_predictor
from model.normals.estimator import MAP_NAMES


def save(path: Path, priors: tuple[str, ...], fusion: str) -> Path:
    det = Detector(ModelConfig.from_preset("tiny", priors, fusion, 32))
    det.init_weights(torch.Generator().manual_seed(0))
    save_checkpoint(path, det, threshold=0.5, threshold_rule="test")
    return path


def maps(seed: int, shape: tuple[int, int] = (48, 64)) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(seed)
    a = rng.uniform(0, np.pi, shape)
    return {"intensity": rng.uniform(0, 1, shape).astype(np.float32),
            "dolp": rng.uniform(0, 0.3, shape).astype(np.float32),
            "aolp_cos": np.cos(2 * a).astype(np.float32), "aolp_sin": np.sin(2 * a).astype(np.float32)}


@pytest.mark.parametrize(("fusion", "early_exit"), [("fused", None), ("ensemble", None), ("ensemble", 0.0)])
def test_the_predictor_scores_as_the_station_detector(tmp_path: Path, fusion: str, early_exit: float | None) -> None:
    from station.model_detector import DraemDetector

    path = save(tmp_path / "m", ("intensity", "dolp", "aolp"), fusion)
    pred = load_predictor(path, "cpu", "fp32", early_exit_margin=early_exit)
    det = DraemDetector(path, "cpu", "fp32", early_exit_margin=early_exit)
    assert pred.priors == det.priors == ("intensity", "dolp", "aolp_cos", "aolp_sin")
    assert (pred.model_id, pred.threshold, pred.precision) == (det.model_id, det.threshold, det.precision)
    for seed in range(3):
        p = pred.predict(maps(seed))
        score, heat, ref = p.score, p.heatmap, det.infer(maps(seed))
        assert heat.dtype == np.float32 and heat.shape == (48, 64)
        assert score == ref.score and np.array_equal(heat, ref.heatmap)
        assert not heat[:, :8].any() and not heat[:, 56:].any()  # roi "center": the 48 x 48 centre square
    assert pred.members_run == det.members_run > 0
    assert pred.warm_up(1) > 0


@pytest.mark.parametrize(("kwargs", "key"), [({"precision": "fp16"}, "[model] precision"),
                                              ({"device": "tpu"}, "[model] device"),
                                              ({"device": "cuda"}, "[model] device")])
def test_a_bad_setting_is_a_model_error_naming_its_key(tmp_path: Path, kwargs: dict, key: str) -> None:
    if kwargs.get("device") == "cuda" and torch.cuda.is_available():
        pytest.skip("this machine has CUDA")
    path = save(tmp_path / "m", ("intensity",), "fused")
    with pytest.raises(ModelError) as excinfo:
        load_predictor(path, **kwargs)
    assert key in str(excinfo.value) and "\n" not in str(excinfo.value)


def test_the_normal_prior_reads_the_estimator_inputs() -> None:
    assert PRIOR_MAPS["normal"] == MAP_NAMES


def save_variation_model(path: Path) -> tuple[Detector, torch.Tensor]:
    """A tiny band detector (test_onnx's) with a variation model that alone decides, fitted on 10 noisy copies of
    ``maps(0)``'s band and calibrated on 2, saved at ``path``: (the detector without it, those 12 parts' priors)."""
    from model.draem.with_variation import add_variation

    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "fused", 32, "band"))
    det.init_weights(torch.Generator().manual_seed(0))
    det.eval()
    x = torch.stack([torch.from_numpy(np.stack([maps(0)[k][8:40] for k in MAP_NAMES])) for _ in range(12)])
    x = x + 0.01 * torch.randn(x.shape, generator=torch.Generator().manual_seed(1))
    save_checkpoint(path, add_variation(det, x[:10], None, x[10:], decision="variation"), threshold=0.5,
                    threshold_rule="test")
    return det, x


@pytest.mark.parametrize("precision", ["fp32", "onnx"])
def test_a_variation_only_decision_skips_the_networks_and_scores_the_same(tmp_path: Path, precision: str,
                                                                          monkeypatch) -> None:
    """The station reads the score and heatmap only: when the variation model alone decides, running the networks
    changes neither, so they are not run (0 members per part) and the answer is the same."""
    if precision == "onnx":
        pytest.importorskip("onnxruntime")
    from model.draem.predictor import Predictor

    det, x = save_variation_model(tmp_path / "v")
    pred = load_predictor(tmp_path / "v", "cpu", precision)
    assert not pred.networks_decide
    p = pred.predict(maps(0))
    assert pred.members_run == 0 and np.isfinite(p.heatmap).all()
    # the variation model's checks (its turn where its warp registers these maps)
    assert {"highlight_fraction", "noise_level", "unseen_fraction"} <= set(p.checks) <= {
        "highlight_fraction", "noise_level", "unseen_fraction", "turn_deg"}
    assert 0.0 <= p.checks["highlight_fraction"] <= 1.0 and 0.0 < p.checks["noise_level"] < 1e6
    assert 0.0 <= p.checks["unseen_fraction"] <= 1.0
    monkeypatch.setattr(Predictor, "networks_decide", property(lambda self: True))  # run them after all
    again = pred.predict(maps(0))
    assert pred.members_run == 1 and again.score == p.score and np.array_equal(p.heatmap, again.heatmap)
    with pytest.raises(ModelError, match="no network ran"):
        det.output(x[:1], {}, {})  # a model without the variation member cannot do without them


def test_a_variation_model_reads_the_frame_around_its_view(tmp_path: Path, monkeypatch) -> None:
    """The predictor gives the variation model's registration the frame around the view (``around_px_of``):
    ``AROUND_PX`` input pixels more on each side at the view's detail, the view at its centre, NaN beyond the frame;
    with ``around_px`` 0, none (the warp replicates the view's border, as before 2026-12-06)."""
    from model.draem.roi import AROUND_PX
    from model.draem.variation import VariationModel

    save_variation_model(tmp_path / "v")
    read = []
    zmaps = VariationModel.zmaps
    monkeypatch.setattr(VariationModel, "zmaps", lambda self, x, signed=False, around=None: (
        read.append((x, around)), zmaps(self, x, signed, around))[1])
    pred = load_predictor(tmp_path / "v", "cpu", "fp32")
    assert pred.around_px == AROUND_PX
    p = pred.predict(maps(0))
    view, around = read[-1]
    a = AROUND_PX
    assert around.shape == (1, view.shape[1], view.shape[2] + 2 * a, view.shape[3] + 2 * a)
    centre = around[..., a:-a, a:-a]
    assert torch.allclose(centre[..., 2:-2, 2:-2], view[..., 2:-2, 2:-2], atol=1e-5)  # the view's own pixels
    # the band (rows 12-35, columns 8-55 of 48 x 64, at 32 x 64) and 12 frame px around: the frame's columns end
    assert torch.isnan(around[..., :, 0]).all() and torch.isfinite(around[..., :, a:-a]).all()
    assert np.isfinite(p.score) and p.checks["unseen_fraction"] == 0.0
    assert load_predictor(tmp_path / "v", "cpu", "fp32", around_px=0).predict(maps(0)) is not None
    assert read[-1][1] is None
