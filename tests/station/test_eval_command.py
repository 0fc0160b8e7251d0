"""``station eval``: one model's report, and the ablation over one fused model per prior set."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from test_run import make_dataset, make_model  # same folder (pytest puts it on sys.path)

from station.cli import main


@pytest.fixture(scope="module")
def setup(tmp_path_factory) -> tuple[Path, Path, Path, Path]:
    tmp = tmp_path_factory.mktemp("eval")
    data = make_dataset(tmp / "ds", n=20)  # test split: 0, 1, 10, 11; 1 and 11 defective
    return tmp, data, make_model(tmp / "r" / "best", ("intensity",)), make_model(tmp / "ra" / "best",
                                                                                 ("intensity", "aolp"))


def test_eval_reports_one_model(setup, capsys) -> None:
    tmp, data, r, _ = setup
    assert main(["eval", "--model", str(r), "--data", str(data), "--no-plots", "--out", str(tmp / "one")]) == 0
    rep = json.loads((tmp / "one" / "eval.json").read_text())
    first = rep["rows"][0]
    assert (first["set"], first["n"], first["anomalous"]) == ("rendered, all defects", 4, 2)
    assert 0.0 <= first["image_auroc"] <= 1.0 and rep["same_dataset_as_training"] is False
    assert "| rendered, all defects |" in capsys.readouterr().out
    # the input channel diagnosis, one row per channel of the model's priors (good parts of the split)
    assert [c["channel"] for c in rep["channels"]] == ["intensity"]
    assert rep["channels"][0]["variance"] > 0 and rep["channels"][0]["adjacent_corr"] is not None


def test_fused_ablation_tabulates_one_model_per_prior_set_in_the_papers_order(setup) -> None:
    tmp, data, r, ra = setup
    out = tmp / "abl"
    assert main(["eval", "--ablation", "--model", f"{ra},{r}", "--data", str(data), "--out", str(out)]) == 0
    rep = json.loads((out / "eval.json").read_text())
    assert [(row["priors"], row["model"]) for row in rep["ablation"]] == [("R", str(r)), ("R+AoLP", str(ra))]
    assert (out / "ablation.png").stat().st_size > 1000
    assert main(["eval", "--model", str(r), "--data", str(data), "--no-plots", "--out", str(tmp / "r-alone")]) == 0
    single = json.loads((tmp / "r-alone" / "eval.json").read_text())["rows"][0]
    assert rep["ablation"][0]["image_auroc"] == pytest.approx(single["image_auroc"])
    assert rep["ablation"][0]["pixel_auroc"] == pytest.approx(single["pixel_auroc"])


def test_eval_refuses_several_models_without_ablation_and_an_ensemble_among_them(setup, tmp_path, capsys) -> None:
    import torch

    from model.draem.checkpoint import save_checkpoint
    from model.draem.config import ModelConfig
    from model.draem.detector import Detector

    _, data, r, ra = setup
    assert main(["eval", "--model", f"{r},{ra}", "--data", str(data)]) == 2
    assert "only with --ablation" in capsys.readouterr().err
    ens = Detector(ModelConfig.from_preset("tiny", ("intensity", "aolp"), "ensemble", 32))
    ens.init_weights(torch.Generator().manual_seed(0))
    save_checkpoint(tmp_path / "ens", ens, threshold=0.5)
    assert main(["eval", "--ablation", "--model", f"{r},{tmp_path / 'ens'}", "--data", str(data),
                 "--out", str(tmp_path / "o")]) == 2
    assert "takes fused models" in capsys.readouterr().err
    assert main(["eval", "--ablation", "--model", str(r), "--data", str(data), "--out", str(tmp_path / "o")]) == 2
    assert "--model A,B" in capsys.readouterr().err


def with_defect_records(data: Path, ds: Path, updates: dict[int, dict]) -> Path:
    """A copy of set ``data`` at ``ds`` whose samples' ``params.json`` defect records are updated with
    ``updates[index]``, as station render writes such keys."""
    import shutil

    shutil.copytree(data, ds)
    for i, keys in updates.items():
        p = ds / f"samples/{i:06d}/params.json"
        params = json.loads(p.read_text())
        params["defect"].update(keys)
        p.write_text(json.dumps(params))
    return ds


def test_eval_reports_detection_by_detectability_on_a_set_with_oracle_values(setup, tmp_path) -> None:
    """Oracle values in params.json (as station render --visibility writes them) add the by-detectability table."""
    _, data, r, _ = setup
    ds = with_defect_records(data, tmp_path / "ds", {  # the two defective test samples
        i: {"snr": {"intensity": snr, "dolp": 0.1, "aolp": 0.2, "normal": 0.0}, "snr_best": "intensity"}
        for i, snr in ((1, 0.5), (11, 42.0))})
    assert main(["eval", "--model", str(r), "--data", str(ds), "--no-plots", "--no-synthetic",
                 "--out", str(tmp_path / "rep")]) == 0
    rows = json.loads((tmp_path / "rep" / "eval.json").read_text())["by_detectability"]
    assert {(row["type"], row["snr_bin"], row["defects"]) for row in rows} == {
        ("all", "<1", 1), ("all", ">10", 1), ("stain", "<1", 1), ("stain", ">10", 1)}
    assert "Detection by detectability" in (tmp_path / "rep" / "eval.md").read_text()


def test_eval_reports_detection_by_defect_size_and_face_with_their_plots(setup, tmp_path) -> None:
    """Rendered defects' sizes and normals in params.json (as station render writes them) add the by-size and
    by-face tables and plots."""
    _, data, r, _ = setup
    ds = with_defect_records(data, tmp_path / "ds", {1: {"radius_mm": 1.2, "visible_px": 900, "normal": [0, 0, 1]},
                                                      11: {"radius_mm": 3.1, "visible_px": 40, "normal": [0, -1, 0]}})
    assert main(["eval", "--model", str(r), "--data", str(ds), "--no-synthetic", "--out", str(tmp_path / "rep")]) == 0
    rep = json.loads((tmp_path / "rep" / "eval.json").read_text())
    assert [(row["type"], row["size"], row["range"], row["defects"]) for row in rep["by_size"]] == [
        ("stain", "radius_mm", "1.2-1.2", 1), ("stain", "radius_mm", "3.1-3.1", 1),
        ("stain", "visible_px", "40-40", 1), ("stain", "visible_px", "900-900", 1)]
    assert "by-size.png" in rep["plots"] and (tmp_path / "rep" / "by-size.png").stat().st_size > 1000
    assert "Detection by defect size" in (tmp_path / "rep" / "eval.md").read_text()
    assert [(row["face"], row["type"], row["defects"]) for row in rep["by_face"]] == [
        ("top", "all", 1), ("top", "stain", 1), ("front", "all", 1), ("front", "stain", 1)]
    assert all(0.0 <= row["caught"] <= 1.0 and 0.0 <= row["image_auroc"] <= 1.0 for row in rep["by_face"])
    assert "by-face.png" in rep["plots"] and (tmp_path / "rep" / "by-face.png").stat().st_size > 1000
    assert "Detection by the face" in (tmp_path / "rep" / "eval.md").read_text()
    import csv  # scores.csv carries each defect's face, for station compare's two-camera table

    faces = {r["index"]: r["face"] for r in csv.DictReader(open(tmp_path / "rep" / "scores.csv"))}
    assert faces["1"] == "top" and faces["11"] == "front" and faces["0"] == ""
