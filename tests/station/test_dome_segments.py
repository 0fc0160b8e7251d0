"""Photometric stereo end to end on a set of two frames per part (the dome's halves): ``station train`` records the
segments, ``station variation`` and ``station eval`` read each part's frames as one (the uniform dome's priors and
the tilt), and a dent seen only in the tilt is found; a model and a set that disagree on frames per part are
refused in one line, and so are a segment model and a segment set at the station, which takes one frame per part."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest
from line_sets import make_line_set, make_segment_set  # same folder (pytest puts it on sys.path)

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
    # the station takes one frame per part: such a model is refused at start in one line naming it
    from station.model_detector import DraemDetector, ModelLoadError

    with pytest.raises(ModelLoadError, match="a frame per dome segment"):
        DraemDetector(model, device="cpu")
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
    with pytest.raises(CameraConfigError, match="a frame per dome segment"):
        VirtualCamera(CameraConfig(), VirtualCameraConfig(dataset=str(pair))).open()
