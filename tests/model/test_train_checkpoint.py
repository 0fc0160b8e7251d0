import json

import numpy as np
import pytest
import torch

from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.config import ModelConfig
from model.draem.detector import Detector, image_scores
from model.draem.errors import CheckpointError
from model.draem.evaluate import evaluate, synthetic_eval_data
from model.draem.train import TensorData, TrainConfig, train

PRIORS = ("intensity", "dolp", "aolp")


def _cfg(fusion: str = "fused", size: int = 32) -> ModelConfig:
    return ModelConfig.from_preset("tiny", PRIORS, fusion, input_size_px=size)


def test_tiny_model_loss_falls(tmp_path, toy):
    x, obj = toy(12, 32)
    res = train(_cfg(), TensorData(x, obj), tmp_path, TrainConfig(steps=30, batch_size=4, eval_every=30),
                progress=False)
    losses = [h["loss"] for h in res.history if "loss" in h]
    assert len(losses) == 30
    assert np.mean(losses[-5:]) < 0.95 * np.mean(losses[:5])
    assert (tmp_path / "best.pt").is_file() and (tmp_path / "best.json").is_file()
    assert 0.0 <= res.best_metrics["pixel_auroc"] <= 1.0


def test_resume_continues_exactly(tmp_path, toy):
    x, obj = toy(8, 32)
    data = TensorData(x, obj)
    tc = dict(batch_size=2, eval_every=3, seed=5)
    straight = train(_cfg("ensemble"), data, tmp_path / "a", TrainConfig(steps=6, **tc), progress=False)
    train(_cfg("ensemble"), data, tmp_path / "b", TrainConfig(steps=6, max_minutes=1e-9, **tc), progress=False)
    resumed = train(_cfg("ensemble"), data, tmp_path / "b", TrainConfig(steps=6, **tc), progress=False)
    assert resumed.steps_done == 6
    la = [h["loss"] for h in straight.history if "loss" in h]
    lb = [h["loss"] for h in resumed.history if "loss" in h]
    assert lb == pytest.approx(la, rel=1e-5)
    with pytest.raises(CheckpointError, match="resuming a different model"):
        train(_cfg("fused"), data, tmp_path / "b", TrainConfig(steps=8, **tc), progress=False)
    for damage in (b"garbage", (tmp_path / "b" / "last.state.pt").read_bytes()[:100]):  # an UnpicklingError
        (tmp_path / "b" / "last.state.pt").write_bytes(damage)  # traceback; a truncated one named no file
        with pytest.raises(CheckpointError, match=r"last\.state\.pt: cannot resume from it"):
            train(_cfg("ensemble"), data, tmp_path / "b", TrainConfig(steps=8, **tc), progress=False)


def test_checkpoint_round_trip_and_mismatch_errors(tmp_path, toy):
    x, obj = toy(4, 32)
    det = Detector(_cfg("ensemble"))
    det.init_weights(torch.Generator().manual_seed(0))
    det.eval()
    pt, js = save_checkpoint(tmp_path / "m", det, threshold=0.42, threshold_rule="test")
    ck = load_checkpoint(tmp_path / "m.pt", expect_priors=PRIORS)
    assert ck.threshold == 0.42 and ck.detector.config == det.config
    a, b = det.predict(x, obj), ck.detector.predict(x, obj)
    assert torch.equal(a.anomaly_map, b.anomaly_map) and torch.equal(a.score, b.score)

    with pytest.raises(CheckpointError, match=r"expected \['dolp'\]"):
        load_checkpoint(tmp_path / "m", expect_priors=("dolp",))
    meta = json.loads(js.read_text())
    js.write_text(json.dumps({**meta, "convention_version": 999}))
    with pytest.raises(CheckpointError, match="convention version 999"):
        load_checkpoint(tmp_path / "m")
    js.write_text(json.dumps({**meta, "model": {**meta["model"], "reconstructive_width": 16}}))
    with pytest.raises(CheckpointError, match=r"m\.pt: .*shape"):
        load_checkpoint(tmp_path / "m", verify_hash=False)
    js.write_text(json.dumps(meta))
    pt.write_bytes(pt.read_bytes()[:-10] + b"0123456789")
    with pytest.raises(CheckpointError, match="sha256"):
        load_checkpoint(tmp_path / "m")
    torch.save({"not": "weights", "obj": ValueError("pickled")}, pt)  # pickled object: refused
    with pytest.raises(CheckpointError, match="cannot load weights safely"):
        load_checkpoint(tmp_path / "m", verify_hash=False)
    pt.unlink()
    with pytest.raises(CheckpointError, match=r"m\.pt: weights file missing"):
        load_checkpoint(tmp_path / "m")
    js.unlink()
    with pytest.raises(CheckpointError, match=r"m\.json: checkpoint sidecar missing"):
        load_checkpoint(tmp_path / "m")


def test_image_score_uses_the_object_region_only():
    amap = torch.zeros(2, 32, 32)
    amap[:, 0:5, 0:5] = 1.0  # strong response on the background
    amap[1, 20:26, 20:26] = 0.5
    obj = torch.zeros(2, 32, 32, dtype=torch.bool)
    obj[:, 10:30, 10:30] = True
    s = image_scores(amap, obj, 5)
    assert float(s[0]) == 0.0 and float(s[1]) == pytest.approx(0.5)
    assert float(image_scores(amap, None, 5)[0]) == pytest.approx(1.0)


def test_synthetic_eval_set_and_evaluate(toy):
    x, obj = toy(8, 32)
    val = synthetic_eval_data(TensorData(x, obj), PRIORS, seed=1)
    assert val.kind == "synthetic" and val.label.sum() > 0
    det = Detector(_cfg("ensemble"))
    res = evaluate(det, val)
    assert res.scores.shape == (8,) and res.maps.shape == (8, 32, 32)
    assert {"image_auroc", "pixel_auroc", "aupro_0.3", "pixel_ap", "image_auroc_dolp"} <= set(res.metrics)


def test_ablation_averages_ensemble_members_in_the_papers_order(toy):
    from station.commands.eval import ablation_rows

    x, obj = toy(8, 32)
    val = synthetic_eval_data(TensorData(x, obj), PRIORS, seed=1)
    det = Detector(_cfg("ensemble"))
    det.init_weights(torch.Generator().manual_seed(3))
    res = evaluate(det, val)
    rows = ablation_rows(res, val)
    # no normal member: the "all" row is left out rather than faked
    assert [r["priors"] for r in rows] == ["R", "R+AoLP", "R+AoLP+DoLP"]
    assert rows[0]["image_auroc"] == pytest.approx(res.metrics["image_auroc_intensity"])
    # all three members averaged is exactly the detector's own fused answer
    assert rows[-1]["image_auroc"] == pytest.approx(res.metrics["image_auroc"])
    np.testing.assert_allclose(np.mean([res.member_maps[m] for m in PRIORS], 0), res.maps, atol=1e-6)
    assert evaluate(Detector(_cfg("fused")), val).member_maps == {}


def test_the_training_module_re_exports_neither_evaluation_nor_runtime():
    import model.draem.train as T

    moved = ("EvalData", "EvalResult", "evaluate", "synthetic_eval_data", "resolve_device", "resolve_precision",
             "autocast")
    assert [n for n in moved if hasattr(T, n)] == []


@pytest.mark.parametrize("given", ["", ".", "/", ".."])
def test_a_model_path_that_names_no_file_is_a_checkpoint_error(given: str) -> None:
    """`--model ""` (or `--out ""`, `--init ""`) raised ValueError "PosixPath('.') has an empty name": a traceback
    in threshold, eval, variation, residual, quantize, adapt, ensemble and train."""
    from model.draem.checkpoint import paths
    from model.draem.errors import CheckpointError

    with pytest.raises(CheckpointError, match="names no checkpoint"):
        paths(given)
