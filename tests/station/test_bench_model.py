"""``station bench model``: one row per configuration plus the normal estimator, written as JSON and Markdown."""

from __future__ import annotations

import json

from station.cli import main


def test_bench_model_rows(tmp_path) -> None:
    assert main(["bench", "model", "--presets", "tiny", "--precisions", "fp32", "--fusions", "ensemble,fused",
                 "--repeats", "1", "--no-baseline", "--out", str(tmp_path)]) == 0
    rows = json.loads((tmp_path / "model.json").read_text())["rows"]
    assert [(r["preset"], r["fusion"], r["networks"]) for r in rows] == [
        ("tiny", "ensemble", 4), ("tiny", "fused", 1), ("normal-net", "-", 1)]
    assert all(r["ms_per_part"] > 0 and r["params_M"] > 0 for r in rows)
    assert "normal-net" in (tmp_path / "model.md").read_text()


def test_bench_model_int8_row_runs_quantized_networks(tmp_path, monkeypatch) -> None:
    from model.draem import onnx_export

    exported, export = [], onnx_export.export_network
    monkeypatch.setattr(onnx_export, "export_network", lambda net, path: exported.append(path) or export(net, path))
    assert main(["bench", "model", "--presets", "tiny", "--precisions", "onnx,int8", "--fusions", "fused",
                 "--repeats", "1", "--no-baseline", "--out", str(tmp_path)]) == 0
    onnx, int8 = json.loads((tmp_path / "model.json").read_text())["rows"][:2]
    assert (onnx["precision"], int8["precision"]) == ("onnx", "int8")
    assert onnx["onnx_max_abs_err"] < 1e-4 < int8["onnx_max_abs_err"]  # int8 really ran, not the fp32 graph
    assert len(exported) == 2  # both rows' networks exported as the station exports them (one fused network each)
