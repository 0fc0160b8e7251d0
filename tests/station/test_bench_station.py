"""``station bench pipeline`` (the real loop over held-out parts, the Pareto front) and ``station bench soak``."""

from __future__ import annotations

import json
from pathlib import Path

from test_run import make_dataset, make_model, write_config  # same folder (pytest puts it on sys.path)

from station.benchmarks.pipeline import label, pareto_front
from station.cli import main


def test_pareto_front_keeps_only_undominated_rows() -> None:
    rows = [{"p99_ms": 50, "image_auroc": 0.90}, {"p99_ms": 80, "image_auroc": 0.95},
            {"p99_ms": 90, "image_auroc": 0.93}, {"p99_ms": 40, "image_auroc": 0.70}]
    assert pareto_front(rows) == [0, 1, 3]  # 2 is slower and worse than 1


def test_label_names_a_training_run_by_its_folder() -> None:
    row = {"checkpoint": "runs/train/fused-R/best", "model": "best-fast-fused-0123abcd", "priors": "intensity",
           "method": "bilinear", "precision": "fp32", "presence": "on"}
    assert label(row) == "fused-R/intensity/bilinear/fp32/presence on"
    assert label({**row, "checkpoint": "model/weights/default"}).startswith("default/")


def test_bench_pipeline_runs_the_station_over_the_grid(tmp_path: Path) -> None:
    model = make_model(tmp_path / "m" / "best")
    data = make_dataset(tmp_path / "ds", n=20)  # test split: indices 0, 1, 10, 11 (two of them defective)
    out = tmp_path / "bench"
    assert main(["bench", "pipeline", "--data", str(data), "--models", str(model), "--methods", "bilinear,superpixel",
                 "--precisions", "fp32", "--parts", "6", "--out", str(out)]) == 0
    report = json.loads((out / "pipeline.json").read_text())
    rows = report["rows"]
    assert [r["method"] for r in rows] == ["bilinear", "superpixel"]
    for r in rows:
        assert r["parts"] == 6 and r["judged"] == 6 and 0 < r["p50_ms"] <= r["p99_ms"]
        assert 0.0 <= r["image_auroc"] <= 1.0 and r["parts_per_s"] > 0
    assert report["front"] and (out / "pipeline.png").stat().st_size > 1000


def test_bench_pipeline_times_a_two_camera_station(tmp_path: Path, capsys) -> None:
    model, side = make_model(tmp_path / "m" / "best"), make_model(tmp_path / "s" / "side", ("intensity",))
    data, twin = make_dataset(tmp_path / "ds", n=20), make_dataset(tmp_path / "twin", n=20)
    out = tmp_path / "bench"
    args = ["bench", "pipeline", "--data", str(data), "--models", str(model), "--methods", "bilinear",
            "--precisions", "fp32", "--presence", "off", "--parts", "6", "--out", str(out)]
    modes = ["--pair-modes", "parallel,serial,first-only"]
    assert main([*args, "--second-model", str(side), "--second-data", str(twin), *modes]) == 0
    rows = json.loads((out / "pipeline.json").read_text())["rows"]
    assert [(r["pair_mode"], r["second_checkpoint"]) for r in rows] == [("parallel", str(side)), ("serial", str(side)),
                                                                         ("first-only", "")]
    assert all(row["parts"] == row["judged"] == 6 and row["p99_ms"] > 0 for row in rows)
    assert "| second_checkpoint | pair_mode |" in (out / "pipeline.md").read_text()
    assert main([*args, "--second-model", str(side)]) == 2
    assert "--second-model and --second-data go together" in capsys.readouterr().err


def test_bench_soak_accounts_for_every_part(tmp_path: Path) -> None:
    cfg = write_config(tmp_path, make_model(tmp_path / "m" / "best"), make_dataset(tmp_path / "ds"))
    out = tmp_path / "soak"
    assert main(["bench", "soak", "--config", str(cfg), "--parts", "12", "--sample-s", "0.2", "--out", str(out)]) == 0
    report = json.loads((out / "soak.json").read_text())
    r = report["result"]
    assert r["rows"] == r["grabbed"] == 12 and r["rows_match"] and len(report["samples"]) >= 2
    assert all(s["rss_mb"] > 10 for s in report["samples"]) and (out / "soak.png").is_file()


def test_bench_pipeline_presence_axis_scores_the_check(tmp_path: Path) -> None:
    import numpy as np
    from test_presence import empty_mosaic, part_mosaic

    from sim.dataset import DatasetSpec, Sample, init_dataset, is_empty, split_of, write_sample

    data = tmp_path / "ds"  # test split 0, 1, 10, 11: 1 and 10 empty, 11 defective
    init_dataset(data, DatasetSpec(seed=3, width=96, height=64, empty_rate=0.5), 20)
    for i in (0, 1, 10, 11):
        empty = is_empty(3, i, 0.5)
        label = int(i == 11)
        params = {"index": i, "split": split_of(i), "label": label, **({"empty": True} if empty else {})}
        write_sample(data, Sample(i, empty_mosaic(i) if empty else part_mosaic(), params, label, split_of(i)))
    out = tmp_path / "bench"
    assert main(["bench", "pipeline", "--data", str(data), "--models", str(make_model(tmp_path / "m" / "best")),
                 "--methods", "bilinear", "--precisions", "fp32", "--presence", "on,off", "--empty-rate", "0.4",
                 "--parts", "10", "--out", str(out)]) == 0
    on, off = json.loads((out / "pipeline.json").read_text())["rows"]
    assert (on["presence"], off["presence"]) == ("on", "off")
    assert on["empty_frames"] == off["empty_frames"] > 0  # the same frames in the same order
    assert on["empty_skipped"] == 1.0 and on["parts_skipped"] == 0.0 and on["presence_p50_ms"] > 0
    assert on["model_runs"] == 10 - on["empty_frames"] and off["model_runs"] == 10
    assert off["empty_skipped"] == 0.0 and np.isnan(off["presence_p50_ms"])
    assert on["judged"] == off["judged"] == 10 - on["empty_frames"]  # AUROC over parts only, both ways
    assert "| presence |" in (out / "pipeline.md").read_text()


def test_bench_pipeline_early_exit_axis_for_ensembles_only(tmp_path: Path) -> None:
    import torch

    from model.draem.checkpoint import save_checkpoint
    from model.draem.config import ModelConfig
    from model.draem.detector import Detector

    ens = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "ensemble", 32))
    ens.init_weights(torch.Generator().manual_seed(0))
    save_checkpoint(tmp_path / "ens", ens, threshold=0.0)  # every part a reject after the first member
    fused = make_model(tmp_path / "fused")
    data = make_dataset(tmp_path / "ds", n=20)
    out = tmp_path / "bench"
    assert main(["bench", "pipeline", "--data", str(data), "--models", f"{tmp_path / 'ens'},{fused}",
                 "--methods", "bilinear", "--precisions", "fp32", "--early-exit", "off,exact", "--parts", "4",
                 "--out", str(out)]) == 0
    rows = json.loads((out / "pipeline.json").read_text())["rows"]
    got = [(r["model"].split("-")[0], r["early_exit"], r["members_per_part"]) for r in rows]
    assert got == [("ens", "off", 3.0), ("ens", "exact", 1.0), ("fused", "off", 1.0)]
    assert main(["bench", "pipeline", "--data", str(data), "--models", str(fused), "--early-exit", "2",
                 "--out", str(out)]) == 2


def test_bench_pipeline_prior_sets_run_part_of_an_ensemble(tmp_path: Path) -> None:
    import torch

    from model.draem.checkpoint import save_checkpoint
    from model.draem.config import ModelConfig
    from model.draem.detector import Detector

    ens = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "ensemble", 32))
    ens.init_weights(torch.Generator().manual_seed(0))
    save_checkpoint(tmp_path / "ens", ens, threshold=0.5)
    fused = make_model(tmp_path / "fused")
    out = tmp_path / "bench"
    assert main(["bench", "pipeline", "--data", str(make_dataset(tmp_path / "ds", n=20)), "--models",
                 f"{tmp_path / 'ens'},{fused}", "--methods", "bilinear", "--precisions", "fp32", "--prior-sets",
                 "R,R+AoLP,R+AoLP+DoLP,all", "--parts", "4", "--out", str(out)]) == 0
    rows = json.loads((out / "pipeline.json").read_text())["rows"]
    got = [(r["model"].split("-")[0], r["priors"], r["members_per_part"]) for r in rows]
    # "R+AoLP+DoLP" is this ensemble's "all" (no normal member): one row; a fused model runs its own priors once
    assert got == [("ens", "intensity", 1.0), ("ens", "intensity+aolp", 2.0), ("ens", "intensity+dolp+aolp", 3.0),
                   ("fused", "intensity+dolp+aolp", 1.0)]
    assert all(r["flagged_good"] != r["flagged_good"] for r in rows[:2])  # NaN: a subset has no threshold
    assert rows[2]["flagged_good"] == rows[2]["flagged_good"]
    assert main(["bench", "pipeline", "--data", str(tmp_path / "ds"), "--models", str(fused), "--prior-sets", "RGB",
                 "--out", str(out)]) == 2


def test_bench_pipeline_drift_axis_computes_the_statistics_the_station_watches(tmp_path: Path, capsys) -> None:
    """``--drift on`` (the default) runs each camera's drift monitor as ``station run`` does when its model records
    frame statistics; ``off`` does not; a model that records none has none either way. A bad value is one line."""
    import torch

    from model.draem.checkpoint import save_checkpoint
    from model.draem.config import ModelConfig
    from model.draem.detector import Detector
    from model.priors.frame_stats import FrameStatistics, StatisticsRange

    watched = tmp_path / "w" / "watched"
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "fused", 32, "center"))
    det.init_weights(torch.Generator().manual_seed(0))
    trained = StatisticsRange.from_frames(FrameStatistics(0.5, 0.6, 0.0, 0.1) for _ in range(5))
    save_checkpoint(watched, det, threshold=0.5, threshold_rule="test", train={"frame_statistics": trained.to_dict()})
    plain = make_model(tmp_path / "m" / "best")  # records no frame statistics
    data = make_dataset(tmp_path / "ds", n=20)
    out = tmp_path / "bench"
    args = ["bench", "pipeline", "--data", str(data), "--methods", "bilinear", "--precisions", "fp32",
            "--presence", "off", "--parts", "4", "--out", str(out)]
    assert main([*args, "--models", f"{watched},{plain}", "--drift", "on,off"]) == 0
    rows = json.loads((out / "pipeline.json").read_text())["rows"]
    assert [(Path(r["checkpoint"]).name, r["drift"]) for r in rows] == [("watched", "on"), ("watched", "off"),
                                                                        ("best", "off"), ("best", "off")]
    assert all(r["parts"] == r["judged"] == 4 for r in rows)
    assert main([*args, "--models", str(plain), "--drift", "maybe"]) == 2
    assert "--drift: 'maybe' is not on or off" in capsys.readouterr().err


def test_bench_pipeline_around_axis_times_the_frame_around_the_view(tmp_path: Path, capsys) -> None:
    """``--around on`` (the default, as ``station run``) gives a variation model's registration the frame around its
    view (``model.draem.roi.AROUND_PX``), ``off`` only the view: one row each, the same parts judged."""
    import numpy as np
    import torch

    from model.draem.checkpoint import save_checkpoint
    from model.draem.config import ModelConfig
    from model.draem.detector import Detector
    from model.draem.roi import AROUND_PX
    from model.draem.with_variation import add_variation

    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "fused", 32, "band"))
    det.init_weights(torch.Generator().manual_seed(0))
    det.eval()
    x = torch.from_numpy(np.random.default_rng(0).uniform(0.2, 0.8, (12, 4, 32, 64)).astype(np.float32))
    model = tmp_path / "v"
    save_checkpoint(model, add_variation(det, x[:10], None, x[10:], decision="variation"), threshold=0.5,
                    threshold_rule="test")
    data = make_dataset(tmp_path / "ds", n=20)
    out = tmp_path / "bench"
    args = ["bench", "pipeline", "--data", str(data), "--models", str(model), "--methods", "bilinear",
            "--precisions", "fp32", "--presence", "off", "--drift", "off", "--parts", "4", "--out", str(out)]
    assert main([*args, "--around", "on,off"]) == 0
    rows = json.loads((out / "pipeline.json").read_text())["rows"]
    assert [(r["around"], r["around_px"]) for r in rows] == [("on", AROUND_PX), ("off", 0)]
    assert all(r["parts"] == r["judged"] == 4 for r in rows)
    assert main([*args, "--around", "maybe"]) == 2
    assert "--around: 'maybe' is not on or off" in capsys.readouterr().err
