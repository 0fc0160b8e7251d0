"""Photometric stereo end to end on a set of two frames per part (the dome's halves): ``station train`` records the
segments, ``station variation`` and ``station eval`` read each part's frames as one (the uniform dome's priors and
the tilt), and a dent seen only in the tilt is found; a model and a set that disagree on frames per part are
refused in one line. At the station (``[camera] dome_segments``) the virtual camera plays each part's frames in
order and the station judges them as ``station eval`` does."""

from __future__ import annotations

import csv
import json
import sqlite3
from pathlib import Path

import numpy as np
import pytest
from line_sets import make_line_set, make_segment_set  # same folder (pytest puts it on sys.path)
from test_run import write_config

from station.cli import main

BASE = ["--preset", "tiny", "--fusion", "fused", "--size", "32", "--steps", "2", "--batch-size", "4",
        "--eval-every", "2", "--device", "cpu", "--roi", "band"]


def variation_auroc(tmp_path: Path, capsys, data: Path, val: Path, priors: str, name: str) -> tuple[float, Path]:
    """Train for 2 steps with ``priors``, add the variation model (it decides), evaluate on ``val``'s parts."""
    assert main(["train", "--data", str(data), "--priors", priors, *BASE, "--out", str(tmp_path / name)]) == 0
    model = tmp_path / f"{name}-v"
    assert main(["variation", "--model", str(tmp_path / name / "last"), "--data", str(data),
                 "--out", str(model)]) == 0
    assert main(["eval", "--model", str(model), "--data", str(val), "--split", "val", "--no-plots",
                 "--no-synthetic", "--out", str(tmp_path / f"{name}-ev")]) == 0
    capsys.readouterr()
    report = json.loads((tmp_path / f"{name}-ev" / "eval.json").read_text())
    return next(r["variation"] for r in report["detectors"] if r["type"] == "all"), model


def test_train_variation_and_eval_find_a_dent_seen_only_in_the_tilt(tmp_path: Path, capsys) -> None:
    data = make_segment_set(tmp_path / "ds", n=40, defective=lambda i: False)
    val = make_segment_set(tmp_path / "val", n=30, seed=5, validation=True)
    with_tilt, model = variation_auroc(tmp_path, capsys, data, val, "intensity,dolp,aolp,tilt_x", "tilt")
    assert with_tilt >= 0.95
    meta = json.loads(model.with_suffix(".json").read_text())
    assert meta["model"]["dome_segments"] == [0.0, 180.0]
    # station eval writes each part's scores, for part-by-part comparisons: the variation model decides here
    with open(tmp_path / "tilt-ev" / "scores.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 30 and {r["label"] for r in rows} == {"0", "1"}
    assert {r["defect_type"] for r in rows if r["label"] == "1"} == {"dent"}
    assert sorted(int(r["index"]) for r in rows) == list(range(30))
    good = [float(r["variation"]) for r in rows if r["label"] == "0"]
    assert min(float(r["variation"]) for r in rows if r["label"] == "1") > sorted(good)[len(good) // 2]
    # the station judges a part on its frames as station eval does; the frames in the other order are another part
    from drivers.frame import Frame
    from model.priors import IMX250MZR
    from sim.dataset import open_dataset
    from station.inspector import Inspector
    from station.model_detector import DraemDetector

    detector = DraemDetector(model, device="cpu")
    assert detector.dome_segments == (0.0, 180.0)
    inspector = Inspector(detector, IMX250MZR, segments=detector.dome_segments)
    scores = {int(r["index"]): float(r["score"]) for r in rows}
    ds = open_dataset(val)
    for i in (0, 1):  # a good part and a dented one
        frames = [Frame(raw, "Mono8", 8, k + 1, 0, 0) for k, raw in enumerate(ds.load(i, ground_truth=False).raws)]
        result = inspector.inspect(frames)
        assert result.score == pytest.approx(scores[i], abs=1e-3)
        assert result.error is None  # the dented part scores high, and did not move: the score is its reason
    # a good part's frames in the other order: the tilt's sign flips, and it scores above every good part
    good_scores = [scores[int(r["index"])] for r in rows if r["label"] == "0"]
    frames = [Frame(raw, "Mono8", 8, k + 1, 0, 0) for k, raw in enumerate(ds.load(0, ground_truth=False).raws)]
    assert inspector.inspect(frames[::-1]).score > max(good_scores)
    # the part moved between its frames (2 px, a whole polarizer superpixel): it scores high, and the reason says why
    moved = [frames[0], Frame(np.ascontiguousarray(np.roll(frames[1].raw, 2, axis=1)), "Mono8", 8, 2, 0, 0)]
    result = inspector.inspect(moved)
    assert result.score is not None and result.score > detector.threshold and result.error is not None
    assert "the part moved 1.9" in result.error and "(at most 0.35 px; score" in result.error
    # station run: the virtual camera plays each part's two frames, the station triggers and judges them as one
    cfg = write_config(tmp_path, model, val, camera="dome_segments = [0.0, 180.0]")
    assert main(["run", "--camera", "sim", "--config", str(cfg), "--frames", "6"]) == 0
    logged = sqlite3.connect(tmp_path / "log.sqlite").execute(
        "SELECT decision, camera_frame_id, image_path FROM inspections ORDER BY id").fetchall()
    assert [r[1] for r in logged] == [1, 3, 5, 7, 9, 11]  # a row per part, naming its first frame
    assert {r[0] for r in logged} <= {"pass", "reject"}
    for _, _, image in logged:
        if image:
            with np.load(image) as f:
                assert f["raw"].shape == f["raw_1"].shape
    capsys.readouterr()
    for line, message in (("", "takes one frame per part, but the model"),
                          ("dome_segments = [180.0, 0.0]", "takes a frame per dome segment at 180, 0 deg, but the "
                                                           "model")):
        write_config(tmp_path, model, val, camera=line)
        assert main(["run", "--camera", "sim", "--config", str(cfg), "--frames", "6"]) == 2
        err = capsys.readouterr().err
        assert message in err and "reads a frame per dome segment at 0, 180 deg: set dome_segments = [0, 180]" in err
        assert len(err.strip().splitlines()) == 1
    # a model of one frame per part does not read a set of two, and the other way round
    one = make_line_set(tmp_path / "one", n=30, seed=2, validation=True)
    assert main(["eval", "--model", str(model), "--data", str(one), "--split", "val", "--no-plots",
                 "--no-synthetic", "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert "one frame per part, the model reads a frame per dome segment at 0, 180 deg" in err
    assert len(err.strip().splitlines()) == 1


def test_a_parts_frames_are_read_as_the_uniform_dome_plus_its_tilt(tmp_path: Path) -> None:
    """What the model reads of a segment set (``station.datasets.load_split``): intensity from the frames' mean, in
    which the dent does not show, and the tilt, in which it does; a set and a model that disagree on frames per part
    are refused."""
    import torch

    from station.datasets import load_split
    from station.errors import UserError

    val = make_segment_set(tmp_path / "val", n=6, validation=True)  # parts 1 and 4 have the dent
    sp = load_split(val, "val", ("intensity", "tilt_x"), (32, 64), progress=False, roi="frame",
                    dome_segments=(0.0, 180.0))
    assert sp.label.tolist() == [0, 1, 0, 0, 1, 0] and sp.priors.shape == (6, 2, 32, 64)
    dent = sp.defect_mask[1]
    step = (sp.priors[1] - sp.priors[0])[:, dent].mean(1)  # dent minus good part, on the dent
    assert abs(float(step[0])) < 0.01 and float(step[1]) > 0.1  # not in intensity; in the tilt
    assert torch.isfinite(sp.priors).all() and float(sp.priors[:, 1].abs().max()) <= 1.0
    with pytest.raises(UserError, match="a frame per dome segment at 0, 180 deg, the model reads one frame per part"):
        load_split(val, "val", ("intensity",), (32, 64), progress=False)


def test_a_tilt_prior_without_its_pair_and_a_segment_set_in_the_virtual_camera_are_refused(tmp_path: Path,
                                                                                          capsys) -> None:
    one = make_line_set(tmp_path / "one", n=20)
    assert main(["train", "--data", str(one), "--priors", "intensity,tilt_x", *BASE, "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err
    assert "tilt_x needs frames at 0 and 180 deg; there is one frame per part" in err
    assert len(err.strip().splitlines()) == 1
    from drivers.camera import CameraConfig
    from drivers.errors import CameraConfigError
    from drivers.virtual_camera import VirtualCamera, VirtualCameraConfig

    pair = make_segment_set(tmp_path / "pair", n=4)
    with pytest.raises(CameraConfigError, match="a frame per dome segment at 0, 180 deg for each part, the camera's "
                                                "frames_per_part is 1: set"):
        VirtualCamera(CameraConfig(), VirtualCameraConfig(dataset=str(pair))).open()
    with pytest.raises(CameraConfigError, match="holds one frame per part, the camera's frames_per_part is 2"):
        VirtualCamera(CameraConfig(frames_per_part=2), VirtualCameraConfig(dataset=str(one))).open()


def test_the_virtual_camera_plays_a_parts_frames_in_the_segments_order(tmp_path: Path) -> None:
    from drivers.camera import CameraConfig
    from drivers.virtual_camera import VirtualCamera, VirtualCameraConfig
    from sim.dataset import open_dataset

    pair = make_segment_set(tmp_path / "pair", n=4)
    ds = open_dataset(pair)
    with VirtualCamera(CameraConfig(frames_per_part=2), VirtualCameraConfig(str(pair), defect_rate=0.5)) as cam:
        cam.start()
        for _ in range(3):
            frames = []
            for _ in range(2):
                cam.trigger()
                frames.append(cam.grab())
            first, second = frames
            index = first.ground_truth.sample_index
            assert second.ground_truth is first.ground_truth and second.frame_id == first.frame_id + 1
            raws = ds.load(index, ground_truth=False).raws
            assert np.array_equal(first.raw, raws[0]) and np.array_equal(second.raw, raws[1])
            assert not np.array_equal(first.raw, second.raw)


def test_capture_and_import_keep_each_parts_frames(tmp_path: Path, capsys) -> None:
    """``station capture`` with ``[camera] dome_segments`` triggers and keeps each part's frames, ``station import``
    makes them a set of the same segments (what ``station adapt`` and ``eval`` read with such a model)."""
    from sim.dataset import open_dataset

    pair = make_segment_set(tmp_path / "pair", n=8, defective=lambda i: False)
    cfg = tmp_path / "station.toml"
    cfg.write_text(f'[camera]\ndome_segments = [0.0, 180.0]\n[sim]\ndataset = "{pair}"\ndefect_rate = 0.0\n')
    out = tmp_path / "cap"
    assert main(["capture", "--camera", "sim", "--config", str(cfg), "--frames", "4", "--out", str(out)]) == 0
    assert "wrote 4 parts of 2 frames" in capsys.readouterr().out
    assert len(list((out / "frame-1" / "train" / "good").iterdir())) == 4
    assert json.loads((out / "polar_ano.json").read_text())["dome_segments"] == [0.0, 180.0]
    assert main(["import", "--from", str(out), "--out", str(tmp_path / "imp"), "--val-fraction", "0"]) == 0
    imp, src = open_dataset(tmp_path / "imp"), open_dataset(pair)
    assert imp.dome_segments == (0.0, 180.0)
    originals = [src.load(i).raws for i in src.indices(None)]
    for i in imp.indices("train"):
        raws = imp.load(i).raws
        assert any(all(np.array_equal(a, b) for a, b in zip(raws, o, strict=True)) for o in originals)
    # station export writes a segment set the same way, and it imports back with its frames
    assert main(["export", "--data", str(pair), "--out", str(tmp_path / "exp")]) == 0
    assert main(["import", "--from", str(tmp_path / "exp"), "--out", str(tmp_path / "back"),
                 "--val-fraction", "0"]) == 0
    back = open_dataset(tmp_path / "back")
    assert back.dome_segments == (0.0, 180.0)
    for i in back.indices(None):
        assert any(all(np.array_equal(a, b) for a, b in zip(back.load(i).raws, o, strict=True)) for o in originals)
    # a set whose later frame is missing is refused in one line naming it
    (out / "frame-1" / "train" / "good" / "000002.png").unlink()
    capsys.readouterr()
    assert main(["import", "--from", str(out), "--out", str(tmp_path / "imp2")]) == 2
    last = capsys.readouterr().err.strip().splitlines()[-1]  # after the progress bar
    assert "frame-1/train/good/000002.png: missing" in last and "names 2 dome segments" in last
