"""``station quantize``: int8 networks beside a checkpoint, used by the station (``precision = "int8"``) and by
``station eval --precision int8``, and refused once the checkpoint's weights change."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import torch
from test_run import make_dataset, make_model  # same folder (pytest puts it on sys.path)

from model.draem.checkpoint import load_checkpoint, save_checkpoint
from station.cli import main
from station.model_detector import DraemDetector, ModelLoadError

pytest.importorskip("onnxruntime")


def test_quantize_then_run_and_eval_in_int8(tmp_path: Path, capsys) -> None:
    data = make_dataset(tmp_path / "ds", n=30, defective=lambda i: i == 12)  # val: 2, 12, 22
    model = make_model(tmp_path / "m" / "last", ("intensity", "aolp"))
    assert main(["quantize", "--model", str(model), "--data", str(data), "--samples", "4"]) == 0
    out = capsys.readouterr().out
    assert "| int8 |" in out and "| fp32 |" in out
    meta = json.loads((tmp_path / "m" / "last.int8" / "int8.json").read_text())
    assert meta["calibration"]["samples"] == 4 and meta["calibration"]["split"] == "train"
    assert meta["calibration"]["method"] == "minmax"  # identical synthetic parts: percentile's histogram cannot run

    assert meta["validation"]["parts"] == 3 and meta["validation"]["decisions_changed"] is not None
    fp32, int8 = DraemDetector(model, "cpu", "fp32"), DraemDetector(model, "cpu", "int8")
    js = tmp_path / "m" / "last.int8" / "int8.json"
    for changed, expected in ((0, "int8"), (2, "fp32")):  # auto: int8 only where they changed few decisions
        js.write_text(json.dumps({**meta, "validation": {**meta["validation"], "decisions_changed": changed}}))
        assert DraemDetector(model, "cpu", "auto").precision == expected
    rng = np.random.default_rng(0)
    priors = {"intensity": rng.random((96, 96), np.float32),
              "aolp_cos": np.ones((96, 96), np.float32), "aolp_sin": np.zeros((96, 96), np.float32)}
    a, b = fp32.infer(priors), int8.infer(priors)
    assert b.heatmap.shape == (96, 96) and np.isfinite(b.heatmap).all() and abs(a.score - b.score) < 0.1

    assert main(["eval", "--model", str(model), "--data", str(data), "--split", "val", "--precision", "int8",
                 "--no-plots", "--no-synthetic", "--out", str(tmp_path / "ev")]) == 0
    assert json.loads((tmp_path / "ev" / "eval.json").read_text())["precision"] == "int8"

    ck = load_checkpoint(model)  # retrained: other weights, so the int8 copies are stale
    with torch.no_grad():
        next(ck.detector.parameters()).add_(0.01)
    save_checkpoint(model, ck.detector, 0.5, "test")
    with pytest.raises(ModelLoadError, match="rerun `station quantize`"):
        DraemDetector(model, "cpu", "int8")


def test_int8_without_quantize_names_the_missing_file(tmp_path: Path) -> None:
    model = make_model(tmp_path / "m" / "last", ("intensity",))
    assert DraemDetector(model, "cpu", "auto").precision == "fp32"
    with pytest.raises(ModelLoadError, match=r"last\.int8/int8\.json.*station quantize"):
        DraemDetector(model, "cpu", "int8")


def test_the_shipped_model_has_no_int8_networks_so_auto_runs_fp32() -> None:
    """Why it ships without them: tests/station/test_pipeline_stress.py, model/weights/README.md ("Int8")."""
    from model.draem.predictor import auto_precision

    shipped = Path(__file__).resolve().parents[2] / "model" / "weights" / "default"
    assert auto_precision(shipped, torch.device("cpu")) == "fp32"
