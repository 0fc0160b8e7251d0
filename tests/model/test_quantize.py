"""Int8 quantization: the copies are really int8, score close to fp32, and are refused once they no longer match
the weights they came from."""

from __future__ import annotations

import json

import pytest
import torch

from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.draem.errors import ModelError
from model.draem.quantize import fit_for_auto, int8_dir, load_int8, quantize_detector, record_check

pytest.importorskip("onnxruntime")
onnx = pytest.importorskip("onnx")

INT8_SCORE_BOUND = 0.1
"""Largest |int8 - fp32| image score accepted here (tiny random network; the shipped model: see its stress test)."""


def _priors(n: int, seed: int) -> torch.Tensor:
    g = torch.Generator().manual_seed(seed)
    intensity = torch.rand(n, 1, 32, 32, generator=g)
    phi = torch.rand(n, 1, 32, 32, generator=g) * torch.pi
    return torch.cat((intensity, torch.cos(2 * phi), torch.sin(2 * phi)), 1)


def test_int8_copies_are_int8_score_close_and_tied_to_their_weights(tmp_path) -> None:
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "aolp"), "fused", 32)).eval()  # test_run's make_model
    det.init_weights(torch.Generator().manual_seed(1))
    folder = quantize_detector(det, _priors(8, 0), int8_dir(tmp_path / "m"), "a" * 64, {"data": "test"})
    assert folder == tmp_path / "m.int8"
    assert json.loads((folder / "int8.json").read_text())["calibration"]["method"] == "percentile"
    ops = {n.op_type for n in onnx.load(str(folder / "fused.onnx")).graph.node}
    assert {"QuantizeLinear", "DequantizeLinear"} <= ops  # QDQ format: convs run on int8 tensors

    int8 = load_int8(det, folder, "a" * 64, threads=1)
    x = _priors(4, 2)  # parts the calibration never saw
    a, b = int8.predict(x), det.predict(x)
    assert torch.isfinite(a.anomaly_map).all() and 0 <= float(a.anomaly_map.min()) <= float(a.anomaly_map.max()) <= 1
    assert float((a.score - b.score).abs().max()) <= INT8_SCORE_BOUND
    assert not torch.equal(a.anomaly_map, b.anomaly_map)  # an approximation, not the fp32 network

    with pytest.raises(ModelError, match="other weights"):
        load_int8(det, folder, "b" * 64)
    (folder / "fused.onnx").write_bytes((folder / "fused.onnx").read_bytes()[:-10])
    with pytest.raises(ModelError, match="changed since"):
        load_int8(det, folder, "a" * 64)
    with pytest.raises(ModelError, match="station quantize"):
        load_int8(det, tmp_path / "elsewhere.int8", "a" * 64)


def test_auto_takes_int8_only_after_a_validation_check_with_few_changed_decisions(tmp_path) -> None:
    (tmp_path / "int8.json").write_text(json.dumps({"format": "polar-ano-int8", "members": {}}))
    assert fit_for_auto(tmp_path) == (False, f"{tmp_path / 'int8.json'}: no validation check of decisions; rerun "
                                             f"`station quantize`")
    record_check(tmp_path, 40, 0, 0.04)
    assert fit_for_auto(tmp_path)[0]
    record_check(tmp_path, 40, 15, 0.1)  # the all-priors ensemble's int8 networks
    assert fit_for_auto(tmp_path) == (False, "int8 changed 15 of 40 validation decisions (over 5%)")
    record_check(tmp_path, 40, None, 0.1)  # no threshold: no decisions to compare
    assert fit_for_auto(tmp_path) == (False, "no decisions to compare (the model has no threshold: `station "
                                             "threshold`, then quantize)")
