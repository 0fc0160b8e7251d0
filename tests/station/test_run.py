"""``station run`` end to end: station.toml -> checkpoint -> virtual camera -> simulated PLC (pty) -> SQLite log."""

from __future__ import annotations

import json
import sqlite3
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
import torch

from model.draem.checkpoint import save_checkpoint
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.priors.mosaic import stokes_to_mosaic
from model.priors.testing import detailed_stokes
from sim.dataset import DatasetSpec, Sample, init_dataset, split_of, write_sample
from station.cli import main

W, H = 96, 64


def make_dataset(root: Path, n: int = 10, defective: Callable[[int], bool] = lambda i: i % 2 == 1) -> Path:
    """Polarized mosaics of a detailed scene; ``defective`` samples (default: odd) carry a defect (a bright patch)
    and its mask."""
    init_dataset(root, DatasetSpec(width=W, height=H), n)
    s0, s1, s2 = detailed_stokes(H, W)
    for i in range(n):
        raw = np.clip(stokes_to_mosaic(s0, s1, s2) * 200, 0, 255).astype(np.uint8)
        mask = np.zeros((H, W), bool)
        if defective(i):
            mask[20:30, 40:50] = True
            raw[mask] = 255
        label = int(mask.any())
        write_sample(root, Sample(i, raw, {"index": i, "split": split_of(i), "label": label,
                                           "defect": {"type": "stain"} if label else None}, label, split_of(i),
                                  defect_mask=mask, object_mask=np.ones((H, W), bool)))
    return root


def make_model(path: Path, priors: tuple[str, ...] = ("intensity", "dolp", "aolp"), roi: str = "center") -> Path:
    det = Detector(ModelConfig.from_preset("tiny", priors, "fused", 32, roi))
    det.init_weights(torch.Generator().manual_seed(0))
    save_checkpoint(path, det, threshold=0.5, threshold_rule="test")
    return path


def write_config(tmp: Path, model: Path, dataset: Path, extra: str = "", camera: str = "") -> Path:
    """``station.toml`` for a simulated run; ``camera``: more ``[camera]`` lines, ``extra``: more tables."""
    cfg = tmp / "station.toml"
    cfg.write_text(f"""
[camera]
frame_rate_hz = 20.0
{camera}
[acquisition]
cycle_time_ms = 60000.0
backpressure = "block"
[model]
path = "{model}"
[sim]
dataset = "{dataset}"
defect_rate = 0.5
[log]
path = "{tmp / 'log.sqlite'}"
image_dir = "{tmp / 'rejects'}"
{extra}
""")
    return cfg


@pytest.fixture
def setup(tmp_path: Path) -> tuple[Path, Path, Path]:
    return tmp_path, make_model(tmp_path / "model" / "best"), make_dataset(tmp_path / "ds")


def test_sim_run_logs_every_part_and_scores_against_ground_truth(setup, capsys) -> None:
    tmp, model, ds = setup
    cfg = write_config(tmp, model, ds)
    assert main(["run", "--camera", "sim", "--config", str(cfg), "--frames", "8",
                 "--summary-json", str(tmp / "s.json")]) == 0
    rows = sqlite3.connect(tmp / "log.sqlite").execute(
        "SELECT decision, part_id, score, threshold, model_id, ground_truth_label, io_delivered, image_path,"
        " demosaic_ms, model_ms, decision_ms, io_ms FROM inspections ORDER BY id").fetchall()
    assert len(rows) == 8
    assert [r[1] for r in rows] == [f"P{i}" for i in range(1, 9)]  # the simulated PLC's part ids, in order
    for decision, _, score, thr, model_id, truth, delivered, image, demosaic_ms, model_ms, decision_ms, io_ms in rows:
        assert decision in ("pass", "reject") and 0.0 <= score <= 1.0 and thr == 0.5
        assert model_id.startswith("best-tiny-fused-") and truth in (0, 1) and delivered == 1
        assert demosaic_ms > 0 and model_ms > 0 and decision_ms >= 0 and io_ms >= 0  # every stage timed
        assert (decision == "reject") == (score > 0.5)
        if decision == "reject":
            with np.load(image) as f:  # the rejected part's raw mosaic and frame-sized heatmap are kept
                assert f["raw"].shape == (H, W) and f["heatmap"].shape == (H, W)
        else:
            assert image is None
    summary = json.loads((tmp / "s.json").read_text())
    assert summary["parts"] == 8 and sum(summary["confusion"].values()) == 8
    assert 0.0 <= summary["collector_pause_max_ms"] < 1000.0  # the run's longest garbage collection (station.heap)
    truths = [r[5] for r in rows]
    assert summary["confusion"].get("bad_pass", 0) + summary["confusion"].get("bad_reject", 0) == sum(truths)
    assert "good part" in capsys.readouterr().out


@pytest.mark.parametrize(("case", "message"), [
    ("missing", "model not found"),
    ("normal", "normal estimator"),
    ("object_roi", "retrain with --roi center"),
    ("serial_no_port", "[io] port"),
])
def test_start_up_errors_are_one_line(setup, capsys, case: str, message: str) -> None:
    tmp, model, ds = setup
    extra = ""
    if case == "missing":
        model = tmp / "nowhere" / "best"
    elif case == "normal":
        model = make_model(tmp / "m2" / "best", ("intensity", "normal"))
    elif case == "object_roi":
        model = make_model(tmp / "m3" / "best", roi="object")
    else:
        extra = '[io]\nmode = "serial"\n'
    cfg = write_config(tmp, model, ds, extra)
    assert main(["run", "--config", str(cfg), "--frames", "2"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0], err
    if case != "serial_no_port":
        assert not (tmp / "log.sqlite").exists()  # the model is checked before anything is opened


def test_viewer_run_ends_with_the_frames(setup, monkeypatch) -> None:
    pytest.importorskip("pyqtgraph")
    monkeypatch.setenv("QT_QPA_PLATFORM", "offscreen")
    tmp, model, ds = setup
    cfg = write_config(tmp, model, ds)
    assert main(["run", "--config", str(cfg), "--frames", "4", "--viewer"]) == 0  # returns: the window closed itself
    assert sqlite3.connect(tmp / "log.sqlite").execute("SELECT COUNT(*) FROM inspections").fetchone()[0] == 4


def test_a_viewer_run_whose_station_fails_does_not_exit_as_if_it_had_run(setup, monkeypatch) -> None:
    """With ``--viewer`` the station runs on a thread of its own; what ended that thread used to vanish, and the
    command exited 0."""
    pytest.importorskip("pyqtgraph")
    monkeypatch.setenv("QT_QPA_PLATFORM", "offscreen")
    from station.loop import Station

    def broken(self, max_parts=None, progress_every_s=5.0):
        raise RuntimeError("acquisition thread could not start")

    monkeypatch.setattr(Station, "run", broken)
    tmp, model, ds = setup
    with pytest.raises(RuntimeError, match="could not start"):
        main(["run", "--config", str(write_config(tmp, model, ds)), "--frames", "4", "--viewer"])


def test_viewer_run_stops_cleanly_on_sigterm(setup) -> None:
    """With ``--viewer`` the station runs beside the Qt loop; SIGTERM used to kill the process (no summary, parts in
    flight unanswered). Now it stops as without a viewer: every trigger answered and logged, the summary written."""
    import os
    import signal
    import subprocess
    import sys
    import time

    pytest.importorskip("pyqtgraph")
    tmp, model, ds = setup
    cfg = write_config(tmp, model, ds)
    env = {**os.environ, "QT_QPA_PLATFORM": "offscreen", "PYTHONPATH": str(Path(__file__).resolve().parents[2])}
    proc = subprocess.Popen([sys.executable, "-m", "station", "run", "--config", str(cfg), "--viewer",
                             "--summary-json", str(tmp / "s.json")], env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120
        rows = 0
        while rows < 3 and time.monotonic() < deadline and proc.poll() is None:
            time.sleep(0.2)
            if (tmp / "log.sqlite").exists():
                try:
                    rows = sqlite3.connect(tmp / "log.sqlite").execute("SELECT COUNT(*) FROM inspections").fetchone()[0]
                except sqlite3.OperationalError:
                    rows = 0
        assert rows >= 3, proc.stderr.read() if proc.poll() is not None else "no rows in time"
        proc.send_signal(signal.SIGTERM)
        out, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 0, err[-2000:]
    assert "summary:" in out
    summary = json.loads((tmp / "s.json").read_text())
    logged = sqlite3.connect(tmp / "log.sqlite").execute("SELECT COUNT(*) FROM inspections").fetchone()[0]
    assert summary["plc_link"]["triggers"] == logged >= 3  # every part announced has its row


def test_a_threshold_of_one_is_warned_about(setup, caplog) -> None:
    """Scores lie in [0, 1]: at threshold 1 no part is rejected on its score (the fault bench uses it on purpose;
    on a line it would pass every defect), so the station says so when it starts."""
    tmp, model, ds = setup
    cfg = write_config(tmp, model, ds, "[decision]\nthreshold = 1.0\n")
    assert main(["run", "--config", str(cfg), "--frames", "1"]) == 0
    assert any("rejects no part on its score" in r.message for r in caplog.records)


def test_an_image_folder_that_is_a_file_stops_the_station_before_the_first_part(setup, capsys) -> None:
    """`[log] image_dir` naming a file: the station ran and logged one error per reject, keeping no image."""
    tmp, model, ds = setup
    (tmp / "rejects").write_text("a file")
    cfg = write_config(tmp, model, ds)  # image_dir = tmp/rejects
    assert main(["run", "--config", str(cfg), "--frames", "2"]) == 2
    assert "[log] image_dir" in capsys.readouterr().err
