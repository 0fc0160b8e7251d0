"""Hostile model files and settings: every number that reaches a decision is checked where it is loaded, and every
bad file or key gives one line naming it (never a traceback, never a station that passes every part)."""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import pytest
import torch

from model.draem.checkpoint import paths, save_checkpoint
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from station.decision import decide
from station.errors import USER_ERRORS
from station.model_detector import DraemDetector


def save(path: Path) -> Path:
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp"), "fused", 32, "center"))
    det.init_weights(torch.Generator().manual_seed(0))
    save_checkpoint(path, det, threshold=0.5, threshold_rule="test")
    return path


def edit_sidecar(path: Path, **changes: object) -> Path:
    _, js = paths(path)
    meta = json.loads(js.read_text())
    for key, value in changes.items():
        if "." in key:  # nested: "normalization.std"
            outer, inner = key.split(".")
            meta[outer][inner] = value
        else:
            meta[key] = value
    js.write_text(json.dumps(meta, allow_nan=True))
    return path


def one_line_error(excinfo: pytest.ExceptionInfo, *needles: str) -> None:
    assert isinstance(excinfo.value, USER_ERRORS), f"{type(excinfo.value).__name__} is not a user error"
    text = str(excinfo.value)
    assert "\n" not in text
    for n in needles:
        assert n in text, f"{n!r} not in {text!r}"


@pytest.mark.parametrize("threshold", [float("nan"), float("inf"), 2.0, -0.1, "abc", [0.5], True])
def test_a_threshold_in_the_model_file_that_cannot_decide_is_refused(tmp_path: Path, threshold: object) -> None:
    path = edit_sidecar(save(tmp_path / "m"), threshold=threshold)
    with pytest.raises(Exception) as excinfo:
        DraemDetector(path, "cpu", "fp32")
    one_line_error(excinfo, "m.json", "threshold")


@pytest.mark.parametrize(("key", "value"), [
    ("normalization.std", [0.0, 1.0]), ("normalization.std", [float("nan"), 1.0]),
    ("normalization.mean", [float("inf"), 0.0]), ("normalization.mean", [0.1]), ("normalization.std", "x"),
])
def test_normalisation_statistics_must_be_finite_and_fit_the_channels(tmp_path: Path, key: str, value: object) -> None:
    path = edit_sidecar(save(tmp_path / "m"), **{key: value})
    with pytest.raises(Exception) as excinfo:
        DraemDetector(path, "cpu", "fp32")
    one_line_error(excinfo, "m.json", key.split(".")[0])


def test_a_finite_threshold_in_range_still_loads(tmp_path: Path) -> None:
    assert DraemDetector(edit_sidecar(save(tmp_path / "m"), threshold=0.25), "cpu", "fp32").threshold == 0.25


@pytest.mark.parametrize("threshold", [float("nan"), float("inf"), None])
def test_decide_rejects_when_the_threshold_is_not_a_number(threshold: object) -> None:
    d = decide(0.01, threshold)  # type: ignore[arg-type]
    assert d.decision == "reject" and "threshold" in d.reason


def test_a_sidecar_that_is_not_an_object_is_named(tmp_path: Path) -> None:
    path = save(tmp_path / "m")
    paths(path)[1].write_text("[]")
    with pytest.raises(Exception) as excinfo:
        DraemDetector(path, "cpu", "fp32")
    one_line_error(excinfo, "m.json", "object")


@pytest.mark.parametrize("weights_file", ["../m.pt", "sub/m.pt", "/etc/passwd", ".."])
def test_weights_file_must_be_a_plain_name_in_the_model_folder(tmp_path: Path, weights_file: str) -> None:
    path = save(tmp_path / "m")
    (tmp_path / "sub").mkdir()
    shutil.copy(paths(path)[0], tmp_path / "sub" / "m.pt")
    path = edit_sidecar(path, weights_file=weights_file)
    with pytest.raises(Exception) as excinfo:
        DraemDetector(path, "cpu", "fp32")
    one_line_error(excinfo, "m.json", "weights_file")


@pytest.mark.parametrize("model_path", ["", "/", "."])
def test_a_model_path_that_names_no_model_is_one_line(model_path: str) -> None:
    with pytest.raises(Exception) as excinfo:
        DraemDetector(model_path, "cpu", "fp32")
    one_line_error(excinfo, "[model] path")


@pytest.mark.parametrize("precision", ["int8", "auto"])
def test_an_int8_record_that_is_a_list_is_named(tmp_path: Path, precision: str) -> None:
    pytest.importorskip("onnxruntime")
    path = save(tmp_path / "m")
    (tmp_path / "m.int8").mkdir()
    (tmp_path / "m.int8" / "int8.json").write_text("[1, 2]")
    if precision == "auto":  # auto falls back to fp32 and says why; it must not crash
        assert DraemDetector(path, "cpu", precision).precision == "fp32"
        return
    with pytest.raises(Exception) as excinfo:
        DraemDetector(path, "cpu", precision)
    one_line_error(excinfo, "int8.json")


@pytest.mark.skipif(torch.cuda.is_available(), reason="this machine has CUDA")
def test_cuda_without_cuda_blames_the_device_not_the_weights(tmp_path: Path) -> None:
    with pytest.raises(Exception) as excinfo:
        DraemDetector(save(tmp_path / "m"), "cuda", "fp32")
    one_line_error(excinfo, "[model] device", "cuda")
    assert "weights" not in str(excinfo.value)


def test_nan_threshold_in_the_model_never_passes_a_part() -> None:
    """The failure of the issue: NaN compared with a score is False, so `score > NaN` never rejected."""
    assert all(decide(s, math.nan).decision == "reject" for s in (0.0, 0.5, 1.0))
