"""ONNX export: every member exported, ONNX Runtime agrees with torch (maps and scores), batches work, one file per
network with the batch as its only dynamic axis, quietly, for the band's wide input too; one trace per architecture,
refilled with each network's weights and never trusted where torch disagrees."""

from __future__ import annotations

from types import SimpleNamespace

import pytest
import torch

from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.draem.onnx_export import BATCH_AXIS, MAX_ABS_ERROR, OnnxDetector, export_network, export_onnx

pytest.importorskip("onnxruntime")

BAND = ("tiny", ("intensity", "dolp", "aolp"), "fused", 32, "band")
"""The architecture of test_variation's and test_predictor's ONNX networks too: exported once per process, then
refilled (``export_network``), so those tests pay no second trace."""


@pytest.fixture
def traces(monkeypatch) -> list:
    """One item per trace of the exporter (``torch.onnx.export`` call) during the test."""
    calls, trace = [], torch.onnx.export
    monkeypatch.setattr(torch.onnx, "export", lambda *a, **k: calls.append(1) or trace(*a, **k))
    return calls


def test_onnx_detector_matches_torch_for_an_ensemble(tmp_path, traces: list) -> None:
    """Two members of one architecture (one channel each): the second is refilled into the first one's trace."""
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp"), "ensemble", 32, "band"))
    det.init_weights(torch.Generator().manual_seed(1))
    det.eval()
    files = export_onnx(det, tmp_path / "x")
    assert len(traces) <= 1  # the second member refilled (none traced if an earlier test kept this architecture)
    assert sorted(files) == ["dolp", "intensity"] and all(f.stat().st_size > 1000 for f in files.values())
    onnx = OnnxDetector.from_files(det, files)  # the files just written (from_detector: test_predictor's onnx)
    x = torch.rand(3, 2, 32, 64, generator=torch.Generator().manual_seed(2))  # batch of 3: dynamic batch axis
    a, b = onnx.predict(x), det.predict(x)
    assert a.anomaly_map.shape == (3, 32, 64)
    assert float((a.anomaly_map - b.anomaly_map).abs().max()) <= MAX_ABS_ERROR
    assert float((a.score - b.score).abs().max()) <= MAX_ABS_ERROR
    assert set(a.member_scores) == {"intensity", "dolp"}
    assert float((a.member_maps["intensity"] - a.member_maps["dolp"]).abs().max()) > 1e-3  # each its own weights


def test_export_network_writes_one_quiet_file_with_a_dynamic_batch_that_runs_a_band_models_wide_input(
        tmp_path, capsys) -> None:
    """One export (each costs ~10 s of the dynamo exporter) checks the file, the axes, the quiet and the band."""
    onnx = pytest.importorskip("onnx")
    det = Detector(ModelConfig.from_preset(*BAND))
    det.init_weights(torch.Generator().manual_seed(1))
    net = det.members["fused"].train()
    f = export_network(net, tmp_path / "a" / "fused.onnx")
    assert not net.training  # exported and left in eval mode
    assert [p.name for p in (tmp_path / "a").iterdir()] == ["fused.onnx"]  # weights inside: no external data file
    graph = onnx.load(str(f)).graph
    dims = {v.name: [d.dim_param or d.dim_value for d in v.type.tensor_type.shape.dim]
            for v in (*graph.input, *graph.output)}
    assert dims == {"x": [BATCH_AXIS, 4, 32, 64], "map": [BATCH_AXIS, 32, 64]}
    out = capsys.readouterr()
    assert out.out == "" and out.err == ""
    det.eval()
    x = torch.rand(2, 4, 32, 64, generator=torch.Generator().manual_seed(2))
    a, b = OnnxDetector.from_files(det, {"fused": f}).predict(x), det.predict(x)
    assert a.anomaly_map.shape == (2, 32, 64)
    assert float((a.anomaly_map - b.anomaly_map).abs().max()) <= MAX_ABS_ERROR


def test_a_second_network_of_an_architecture_is_its_own_weights_in_the_first_ones_trace(tmp_path, traces: list) -> None:
    """Other weights and other batch-norm statistics (folded into the convolutions by the optimiser), no trace."""
    nets = []
    for seed in (1, 2):
        det = Detector(ModelConfig.from_preset(*BAND))
        det.init_weights(torch.Generator().manual_seed(seed))
        for m in det.modules():
            if isinstance(m, torch.nn.BatchNorm2d):
                m.running_mean.uniform_(-0.5, 0.5, generator=torch.Generator().manual_seed(seed))
                m.running_var.uniform_(0.5, 2.0, generator=torch.Generator().manual_seed(seed))
        nets.append(det.eval())
    export_network(nets[0].members["fused"], tmp_path / "a.onnx")
    first = len(traces)  # 1, or 0 after the band test in the same process
    export_network(nets[1].members["fused"], tmp_path / "b.onnx")
    assert len(traces) == first <= 1
    x = torch.rand(2, 4, 32, 64, generator=torch.Generator().manual_seed(3))
    maps = []
    for det, name in zip(nets, ("a", "b"), strict=True):
        a, b = OnnxDetector.from_files(det, {"fused": tmp_path / f"{name}.onnx"}).predict(x), det.predict(x)
        assert float((a.anomaly_map - b.anomaly_map).abs().max()) <= MAX_ABS_ERROR
        maps.append(a.anomaly_map)
    assert float((maps[0] - maps[1]).abs().max()) > 1e-3  # two networks, not one file twice


class _Scaled(torch.nn.Module):
    """A network whose output depends on more than its weights: a Python number, traced into the graph."""

    config = SimpleNamespace(in_channels=1, input_shape=(8, 8))

    def __init__(self, scale: float) -> None:
        super().__init__()
        self.weight, self.scale = torch.nn.Parameter(torch.ones(8, 8)), scale

    def forward(self, x: torch.Tensor) -> SimpleNamespace:
        return SimpleNamespace(anomaly_map=x[:, 0] * self.weight * self.scale)


def test_a_refilled_trace_that_torch_contradicts_is_traced_afresh(tmp_path, monkeypatch) -> None:
    import onnxruntime as ort

    from model.draem import onnx_export

    checks, agrees = [], onnx_export._agrees
    monkeypatch.setattr(onnx_export, "_agrees", lambda *a: checks.append(agrees(*a)) or checks[-1])
    x = torch.rand(1, 1, 8, 8)
    for scale in (1.0, 2.0):  # the same architecture and weights: only the traced-in number differs
        f = export_network(_Scaled(scale), tmp_path / f"{scale}.onnx")
        got = ort.InferenceSession(str(f), providers=["CPUExecutionProvider"]).run(None, {"x": x.numpy()})[0]
        assert float(abs(got - scale * x[:, 0].numpy()).max()) <= MAX_ABS_ERROR
    assert checks == [False]  # the second network was refilled into the first one's trace, caught, and traced anew
