"""ONNX export: every member exported, ONNX Runtime agrees with torch (maps and scores), batches work, one file per
network with the batch as its only dynamic axis, quietly, for the band's wide input too."""

from __future__ import annotations

import pytest
import torch

from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.draem.onnx_export import BATCH_AXIS, MAX_ABS_ERROR, OnnxDetector, export_network, export_onnx

pytest.importorskip("onnxruntime")


def test_onnx_detector_matches_torch_for_an_ensemble(tmp_path) -> None:
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "aolp"), "ensemble", 64))
    det.init_weights(torch.Generator().manual_seed(1))
    det.eval()
    files = export_onnx(det, tmp_path / "x")
    assert sorted(files) == ["aolp", "intensity"] and all(f.stat().st_size > 1000 for f in files.values())
    onnx = OnnxDetector.from_files(det, files)  # the files just written (from_detector: test_predictor's onnx)
    x = torch.rand(3, 3, 64, 64, generator=torch.Generator().manual_seed(2))  # batch of 3: dynamic batch axis
    a, b = onnx.predict(x), det.predict(x)
    assert a.anomaly_map.shape == (3, 64, 64)
    assert float((a.anomaly_map - b.anomaly_map).abs().max()) <= MAX_ABS_ERROR
    assert float((a.score - b.score).abs().max()) <= MAX_ABS_ERROR
    assert set(a.member_scores) == {"intensity", "aolp"}


def test_export_network_writes_one_quiet_file_with_a_dynamic_batch_that_runs_a_band_models_wide_input(
        tmp_path, capsys) -> None:
    """One export (each costs ~10 s of the dynamo exporter) checks the file, the axes, the quiet and the band."""
    onnx = pytest.importorskip("onnx")
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "aolp"), "fused", 32, "band"))
    det.init_weights(torch.Generator().manual_seed(1))
    net = det.members["fused"].train()
    f = export_network(net, tmp_path / "a" / "fused.onnx")
    assert not net.training  # exported and left in eval mode
    assert [p.name for p in (tmp_path / "a").iterdir()] == ["fused.onnx"]  # weights inside: no external data file
    graph = onnx.load(str(f)).graph
    dims = {v.name: [d.dim_param or d.dim_value for d in v.type.tensor_type.shape.dim]
            for v in (*graph.input, *graph.output)}
    assert dims == {"x": [BATCH_AXIS, 3, 32, 64], "map": [BATCH_AXIS, 32, 64]}
    out = capsys.readouterr()
    assert out.out == "" and out.err == ""
    det.eval()
    x = torch.rand(2, 3, 32, 64, generator=torch.Generator().manual_seed(2))
    a, b = OnnxDetector.from_files(det, {"fused": f}).predict(x), det.predict(x)
    assert a.anomaly_map.shape == (2, 32, 64)
    assert float((a.anomaly_map - b.anomaly_map).abs().max()) <= MAX_ABS_ERROR
