"""``station capture``: frames of the configured camera (here the virtual one) into the MVTec layout, with
settings, timestamps and statistics; the folder imports without flags."""

from __future__ import annotations

import json
from pathlib import Path

import cv2
import numpy as np
from line_sets import make_line_set  # same folder (pytest puts it on sys.path)
from test_run import make_model, write_config

from sim.dataset import open_dataset
from station.cli import main


def test_capture_good_and_defective_parts_then_import(tmp_path: Path, capsys) -> None:
    ds = make_line_set(tmp_path / "ds", 20, bit_depth=12)
    model = make_model(tmp_path / "m" / "best")
    cfg = write_config(tmp_path, model, ds)
    out = tmp_path / "cap"
    assert main(["capture", "--camera", "sim", "--config", str(cfg), "--frames", "6", "--out", str(out)]) == 0
    assert "wrote 6 frames (12-bit)" in capsys.readouterr().out
    assert main(["capture", "--camera", "sim", "--config", str(cfg), "--frames", "3", "--out", str(out),
                 "--label", "stain"]) == 0
    assert main(["capture", "--camera", "sim", "--config", str(cfg), "--frames", "2", "--out", str(out)]) == 0
    assert sorted(p.name for p in (out / "train" / "good").iterdir()) == [f"{i:06d}.png" for i in range(8)]
    assert len(list((out / "test" / "stain").iterdir())) == 3
    lines = [json.loads(x) for x in (out / "capture.jsonl").read_text().splitlines()]
    assert len(lines) == 11 and lines[0]["bit_depth"] == 12 and lines[0]["camera"]["exposure_us"] == 10000.0
    assert lines[0]["timestamp_ns"] >= 0 and lines[0]["host_timestamp_ns"] > 0
    assert 0.0 < lines[0]["statistics"]["median_level"] < 1.0
    assert json.loads((out / "polar_ano.json").read_text())["bit_depth"] == 12
    assert main(["import", "--from", str(out), "--out", str(tmp_path / "imp"), "--val-fraction", "0"]) == 0
    imp = open_dataset(tmp_path / "imp")
    assert imp.manifest["bit_depth"] == 12 and len(imp.indices("train")) == 8 and len(imp.indices("test")) == 3
    src = open_dataset(ds)
    raws = [src.load(i).raw for i in src.indices(None)]
    first = imp.load(imp.indices("train")[0]).raw
    assert any(np.array_equal(first, r) for r in raws)  # the camera's mosaic, bit for bit


def test_capture_compares_with_the_models_trained_range(tmp_path: Path, capsys) -> None:
    base = make_line_set(tmp_path / "base", 20)
    assert main(["adapt", "--model", str(make_model(tmp_path / "m" / "best")), "--good", str(base), "--out",
                 str(tmp_path / "m" / "adapted")]) == 0
    dark = make_line_set(tmp_path / "dark", 20, gain=0.5)
    cfg = write_config(tmp_path, tmp_path / "m" / "adapted", dark)
    capsys.readouterr()
    assert main(["capture", "--camera", "sim", "--config", str(cfg), "--frames", "12", "--out",
                 str(tmp_path / "cap"), "--model", str(tmp_path / "m" / "adapted")]) == 0
    out = capsys.readouterr().out
    assert "was trained on: median_level" in out and "raise [camera] exposure_us" in out


def test_capture_keeps_only_frames_the_virtual_cameras_ground_truth_agrees_with(tmp_path: Path, capsys) -> None:
    """Capturing "good" parts from the virtual camera stored its defective parts (drawn at [sim] defect_rate) as
    good: they became a model's good parts."""
    ds = make_line_set(tmp_path / "ds", 20, defective=lambda i: i % 2 == 1)
    cfg = write_config(tmp_path, make_model(tmp_path / "m" / "best"), ds)  # [sim] defect_rate 0.5
    out = tmp_path / "cap"
    assert main(["capture", "--camera", "sim", "--config", str(cfg), "--frames", "8", "--out", str(out)]) == 0
    assert "left out" in capsys.readouterr().out
    assert main(["capture", "--camera", "sim", "--config", str(cfg), "--frames", "4", "--out", str(out),
                 "--label", "stain"]) == 0
    lines = [json.loads(x) for x in (out / "capture.jsonl").read_text().splitlines()]
    assert len(lines) == 12 and [x["ground_truth"] for x in lines] == [0] * 8 + [1] * 4


def test_capture_records_priors_bit_depth_for_a_wider_pixel_format(tmp_path: Path) -> None:
    import time

    from test_loop import ScriptedCamera

    from drivers.frame import Frame
    from station.capture import capture

    class Mono16(ScriptedCamera):  # 12-bit codes in a 16-bit container
        def grab(self, timeout_ms: int | None = None) -> Frame:
            self.frame_id += 1
            return Frame(np.full((8, 8), 4000, np.uint16), "Mono16", 16, self.frame_id, 0, time.time_ns())

    report = capture(Mono16([], trigger="software"), 2, tmp_path / "cap", progress=False, bit_depth=12)
    assert report.bit_depth == 12 and report.stats[0].median_level > 0.9
    assert json.loads((tmp_path / "cap" / "polar_ano.json").read_text())["bit_depth"] == 12


def test_capture_refuses_to_write_into_a_data_set_or_a_model_folder(tmp_path: Path) -> None:
    """`--out` naming a rendered set or a model folder got train/good written inside it."""
    import pytest
    from test_loop import ScriptedCamera

    from station.capture import capture
    from station.errors import UserError

    ds = make_line_set(tmp_path / "ds", 4)
    model = make_model(tmp_path / "m" / "best").parent
    for out in (ds, model):
        with pytest.raises(UserError, match="not a capture folder"):
            capture(ScriptedCamera([0, 0], trigger="software"), 1, out, progress=False)
        assert not (out / "train").exists()


def two_camera_line(tmp_path: Path) -> tuple[Path, Path, Path, Path]:
    """Two virtual cameras on the same 20 parts (every fourth defective), the second's pixels another render's: the
    two sets, a model and the station.toml with ``[second_camera]`` enabled."""
    ds = make_line_set(tmp_path / "ds", 20, defective=lambda i: i % 4 == 1)
    twin = make_line_set(tmp_path / "twin", 20, defective=lambda i: i % 4 == 1, seed=1)  # other pixels, same parts
    model = make_model(tmp_path / "m" / "best")
    cfg = write_config(tmp_path, model, ds, f'[second_camera]\nenabled = true\nmodel = "{model}"\n'
                                            f'dataset = "{twin}"\npresence_rule = "dolp_contrast"\n')
    return ds, twin, model, cfg


def test_capture_with_a_second_camera_writes_twin_folders_that_station_split_reads(tmp_path: Path, capsys) -> None:
    """A two-camera line sets its two thresholds on its own parts: ``station capture --second-out`` writes each
    part's second frame under the same name, the two folders import as twin sets, and ``station split`` reads
    them. Without ``--second-out`` the second camera's frames were grabbed and dropped."""
    ds, twin, model, cfg = two_camera_line(tmp_path)
    out, side = tmp_path / "cap", tmp_path / "cap-side"
    base = ["capture", "--camera", "sim", "--config", str(cfg), "--out", str(out)]
    assert main([*base, "--frames", "2"]) == 2
    assert "[second_camera] is enabled: name --second-out DIR" in capsys.readouterr().err.splitlines()[-1]
    assert main([*base, "--frames", "6", "--second-out", str(side), "--split", "test"]) == 0  # good, never fitted on
    assert main([*base, "--frames", "2", "--second-out", str(side), "--label", "stain"]) == 0
    assert "second camera: wrote 6 frames" in capsys.readouterr().out.split("wrote 2 frames")[0]
    for folder in ("test/good", "test/stain"):
        assert sorted(p.name for p in (out / folder).iterdir()) == sorted(p.name for p in (side / folder).iterdir())
    first, second = ([json.loads(x) for x in (d / "capture.jsonl").read_text().splitlines()] for d in (out, side))
    assert [x["file"] for x in first] == [x["file"] for x in second] and len(first) == 8
    assert [x["ground_truth"] for x in first] == [x["ground_truth"] for x in second] == [0] * 6 + [1] * 2
    src, other = open_dataset(ds), open_dataset(twin)
    for line, frame_dir in ((first, out), (second, side)):  # each folder holds its own camera's mosaics
        raw = cv2.imread(str(frame_dir / line[0]["file"]), cv2.IMREAD_UNCHANGED)
        own, twin_set = (src, other) if frame_dir == out else (other, src)
        assert any(np.array_equal(raw, own.load(i).raw) for i in own.indices(None))
        assert not any(np.array_equal(raw, twin_set.load(i).raw) for i in twin_set.indices(None))
    for d in (out, side):
        assert main(["import", "--from", str(d), "--out", str(d) + "-set"]) == 0
    report = tmp_path / "split.json"
    assert main(["split", "--model", str(model), "--data", f"{out}-set", "--second-model", str(model),
                 "--second-data", f"{side}-set", "--split", "test", "--second-presence-rule", "dolp_contrast",
                 "--max-good-flagged", "0.25", "--budget", "count", "--out", str(report)]) == 0
    split = json.loads(report.read_text())
    assert (split["parts"], split["good"], split["defective"]) == (8, 6, 2)  # both cameras' parts, matched


def test_a_twin_capture_that_fails_on_the_second_camera_leaves_both_folders_twins(tmp_path: Path, monkeypatch,
                                                                                   capsys) -> None:
    """The first camera's frame and line were written before the second camera's; when the second's write failed
    (a full disk), the first folder kept a part the second had not, and every later capture into the pair was
    refused as not twins. A part is now written to both folders or to neither."""
    _, _, _, cfg = two_camera_line(tmp_path)
    out, side = tmp_path / "cap", tmp_path / "cap-side"
    args = ["capture", "--camera", "sim", "--config", str(cfg), "--out", str(out), "--second-out", str(side)]
    real_imwrite, writes = cv2.imwrite, []

    def imwrite(path: str, image: np.ndarray) -> bool:  # the second camera's third frame finds the disk full
        writes.append(path)
        return False if path.startswith(str(side)) and path.endswith("000002.png") else real_imwrite(path, image)

    monkeypatch.setattr(cv2, "imwrite", imwrite)
    assert main([*args, "--frames", "4"]) == 2
    assert "could not write" in capsys.readouterr().err.splitlines()[-1]
    assert any(p.endswith("cap/train/good/000002.png") for p in writes)  # the first camera's frame was written
    monkeypatch.setattr(cv2, "imwrite", real_imwrite)
    for d in (out, side):
        assert sorted(p.name for p in (d / "train" / "good").iterdir()) == ["000000.png", "000001.png"]
        assert [json.loads(x)["file"] for x in (d / "capture.jsonl").read_text().splitlines()] == [
            "train/good/000000.png", "train/good/000001.png"]
    assert main([*args, "--frames", "2"]) == 0  # the pair takes the next parts
    for d in (out, side):
        assert len(list((d / "train" / "good").iterdir())) == 4


def test_capture_compares_the_second_cameras_frames_with_its_own_models_range(tmp_path: Path, capsys) -> None:
    """``--second-model``: the second camera's captured frames against the range its model records, said for that
    camera and its keys; the first camera's against its own (``--model``) stays quiet where its frames are as
    adapted. Without a second camera the option is one line naming it."""
    base = make_line_set(tmp_path / "base", 20)
    assert main(["adapt", "--model", str(make_model(tmp_path / "m" / "best")), "--good", str(base), "--out",
                 str(tmp_path / "m" / "adapted")]) == 0
    adapted = str(tmp_path / "m" / "adapted")
    ds = make_line_set(tmp_path / "ds", 20)
    dark = make_line_set(tmp_path / "dark", 20, gain=0.5)  # the second camera's frames: half as bright
    cfg = write_config(tmp_path, adapted, ds, f'[second_camera]\nenabled = true\nmodel = "{adapted}"\n'
                                              f'dataset = "{dark}"\npresence_rule = "dolp_contrast"\n')
    capsys.readouterr()
    assert main(["capture", "--camera", "sim", "--config", str(cfg), "--frames", "12", "--out", str(tmp_path / "cap"),
                 "--second-out", str(tmp_path / "cap-side"), "--model", adapted, "--second-model", adapted]) == 0
    out = capsys.readouterr().out
    assert f"second camera: {adapted} was trained on: median_level" in out
    warnings = [line for line in out.splitlines() if line.startswith("warning: ")]
    assert len(warnings) == 1 and warnings[0].startswith("warning: second camera: drift over the last 12 frames")
    assert "raise [second_camera] exposure_us" in warnings[0]
    (tmp_path / "one").mkdir()
    one = write_config(tmp_path / "one", adapted, ds)
    assert main(["capture", "--camera", "sim", "--config", str(one), "--frames", "2", "--out", str(tmp_path / "c2"),
                 "--second-model", adapted]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--second-model" in err[0] and "no [second_camera] enabled" in err[0]
