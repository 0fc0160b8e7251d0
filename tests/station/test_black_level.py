"""The station removes a camera's black level before the demosaic: live frames ([camera] black_level), sets that
state one (station import --black-level, a render with a pedestal), and the level measured by station
defect-pixels."""

from __future__ import annotations

import json
import time

import cv2
import numpy as np
import pytest

from drivers.frame import Frame
from model.priors import IMX250MZR
from model.priors.mosaic import stokes_to_mosaic
from station.config import ConfigError, parse_config
from station.errors import UserError
from station.inspector import Inference, Inspector

DOLP = 0.3


class DolpDetector:
    """Scores a part by how far its median DoLP is from the scene's true 0.3: a pedestal read as light lowers it."""

    model_id, threshold, priors = "test-dolp", 0.02, ("dolp",)

    def infer(self, priors):
        return Inference(abs(float(np.median(priors["dolp"])) - DOLP))


def _scene(h: int = 48, w: int = 64, pedestal: int = 64) -> np.ndarray:
    s0 = np.full((h, w), 0.1)
    return np.rint(stokes_to_mosaic(s0, DOLP * s0, 0 * s0) * 4095 + pedestal).astype(np.uint16)


def test_the_inspector_removes_the_black_level_and_rejects_one_above_full_scale() -> None:
    frame = Frame(_scene(), "Mono12", 12, 1, 0, time.time_ns())
    plain = Inspector(DolpDetector(), IMX250MZR).inspect(frame)
    right = Inspector(DolpDetector(), IMX250MZR, black_level=64).inspect(frame)
    assert plain.score > 0.05 and right.score < 0.005  # DoLP 0.228 read as 0.3 again
    frame8 = Frame((_scene() >> 4).astype(np.uint8), "Mono8", 8, 2, 0, time.time_ns())
    wrong = Inspector(DolpDetector(), IMX250MZR, black_level=300).inspect(frame8)
    assert wrong.score is None and "black level 300 must be a whole code in [0, 255)" in wrong.error  # rejected


def test_the_config_key_is_checked_against_the_pixel_format(tmp_path) -> None:
    cfg = parse_config('[camera]\nkind = "aravis"\npixel_format = "Mono12"\nblack_level = 64\n', source="s.toml")
    assert cfg.camera.black_level == 64 and cfg.second_camera.black_level == 0
    with pytest.raises(ConfigError, match=r"^s\.toml: \[camera\] black_level: 300 is not below full scale 255 of "
                                          r"8-bit codes \(Mono8\)$"):
        parse_config('[camera]\nkind = "aravis"\npixel_format = "Mono8"\nblack_level = 300\n', source="s.toml")
    with pytest.raises(ConfigError, match=r"^s\.toml: \[camera\] black_level: -1 is out of range"):
        parse_config("[camera]\nblack_level = -1\n", source="s.toml")


def test_import_states_the_level_and_the_set_s_priors_are_read_without_it(tmp_path) -> None:
    from station.assembly import check_set_black_level
    from station.datasets import load_split, set_black_level
    from station.mvtec import import_mvtec

    src = tmp_path / "captured"
    (src / "train" / "good").mkdir(parents=True)
    for k in range(4):
        cv2.imwrite(str(src / "train" / "good" / f"{k:03d}.png"), _scene(64, 64))
    import_mvtec(src, tmp_path / "plain", bit_depth=12, val_fraction=0.0, progress=False, allow_dark=True)
    import_mvtec(src, tmp_path / "set", bit_depth=12, val_fraction=0.0, progress=False, allow_dark=True, black_level=64)
    manifest = json.loads((tmp_path / "set" / "manifest.json").read_text())
    assert manifest["black_level"] == 64 and set_black_level(tmp_path / "set", manifest) == 64
    assert "black_level" not in json.loads((tmp_path / "plain" / "manifest.json").read_text())
    replay = parse_config("[camera]\nblack_level = 64\n", source="s.toml")  # the virtual camera replaying the set
    check_set_black_level(replay, str(tmp_path / "set"))
    with pytest.raises(ConfigError, match=r"^s\.toml: \[camera\] black_level: 64, but the set .*plain states "
                                          r"black_level 0 \(its frames carry that pedestal\): set black_level = 0$"):
        check_set_black_level(replay, str(tmp_path / "plain"))
    plain = load_split(tmp_path / "plain", "train", ("dolp",), 64, progress=False)
    right = load_split(tmp_path / "set", "train", ("dolp",), 64, progress=False)
    assert float(plain.priors.median()) == pytest.approx(0.228, abs=0.005)
    assert float(right.priors.median()) == pytest.approx(DOLP, abs=0.005)
    with pytest.raises(UserError, match=r"^--black-level: black level 4095 must be a whole code in \[0, 4095\)"):
        import_mvtec(src, tmp_path / "set2", bit_depth=12, val_fraction=0.0, progress=False, allow_dark=True,
                     black_level=4095)
    manifest["black_level"] = "64"
    (tmp_path / "set" / "manifest.json").write_text(json.dumps(manifest))
    with pytest.raises(UserError, match=r"set/manifest\.json: black_level: black level '64' must be a whole code"):
        load_split(tmp_path / "set", "train", ("dolp",), 64, progress=False)  # one line, not a traceback


def test_a_render_with_a_pedestal_states_it_in_its_manifest() -> None:
    from sim.dataset import DatasetSpec, manifest_for
    from sim.sensor import SensorConfig

    assert "black_level" not in manifest_for(DatasetSpec(), 4)
    assert manifest_for(DatasetSpec(sensor=SensorConfig(bit_depth=12, black_level_dn=64)), 4)["black_level"] == 64


def test_the_command_prints_the_black_level_of_the_lens_capped_frames(tmp_path, capsys) -> None:
    from station.cli import main

    rng = np.random.default_rng(2)
    (tmp_path / "frames").mkdir()
    for k in range(6):
        dark = np.clip(np.rint(rng.normal(64, 8, (96, 128))), 0, 4095).astype(np.uint16)
        cv2.imwrite(str(tmp_path / "frames" / f"dark{k}.png"), dark)
        cv2.imwrite(str(tmp_path / "frames" / f"lit{k}.png"), np.clip(np.rint(rng.normal(2000, 30, (96, 128))),
                                                                      0, 4095).astype(np.uint16))
    assert main(["defect-pixels", "--frames", str(tmp_path / "frames"), "--bit-depth", "12",
                 "--out", str(tmp_path / "map.png")]) == 0
    assert ("black level: 64 codes, the median of 6 frame(s) with the lens capped; set [camera] black_level = 64"
            in capsys.readouterr().out)
    for k in range(6):
        (tmp_path / "frames" / f"dark{k}.png").unlink()
    assert main(["defect-pixels", "--frames", str(tmp_path / "frames"), "--bit-depth", "12",
                 "--out", str(tmp_path / "map.png")]) == 0
    assert "black level: not measured" in capsys.readouterr().out


def test_capture_records_the_camera_s_calibration_and_import_and_export_carry_it(tmp_path) -> None:
    """A capture folder names the camera's black level and defect pixel map; `station import` then needs no flags,
    a second capture with another calibration is refused, and an export carries both to the next import."""
    from test_loop import ScriptedCamera

    from model.priors.defect_pixels import read_defect_pixel_map, write_defect_pixel_map
    from sim.dataset import open_dataset
    from station.capture import SensorCalibration, capture
    from station.mvtec import export_mvtec, import_mvtec

    mask = np.zeros((48, 64), bool)
    mask[5, 7] = True
    write_defect_pixel_map(tmp_path / "map.png", mask)

    class Camera(ScriptedCamera):
        def grab(self, timeout_ms: int | None = None) -> Frame:
            self.frame_id += 1
            return Frame(_scene() * 8, "Mono16", 16, self.frame_id, 0, time.time_ns())  # bright enough for 12 bits

    calibration = SensorCalibration(64, str(tmp_path / "map.png"))
    capture(Camera([], trigger="software"), 3, tmp_path / "cap", progress=False, bit_depth=12,
            calibration=calibration)
    info = json.loads((tmp_path / "cap" / "polar_ano.json").read_text())
    assert info["black_level"] == 64 and (read_defect_pixel_map(tmp_path / "cap" / info["defect_pixels"]) == mask).all()
    with pytest.raises(UserError, match=r"taken with black level 64 and a defect pixel map; the camera now has 0 and "
                                        r"none: capture into another folder"):
        capture(Camera([], trigger="software"), 1, tmp_path / "cap", progress=False, bit_depth=12)
    capture(Camera([], trigger="software"), 1, tmp_path / "cap", progress=False, bit_depth=12,
            calibration=calibration)  # the same camera adds frames
    import_mvtec(tmp_path / "cap", tmp_path / "set", val_fraction=0.0, progress=False)  # no flags
    manifest = open_dataset(tmp_path / "set").manifest
    assert manifest["black_level"] == 64 and (read_defect_pixel_map(tmp_path / "set" / manifest["defect_pixels"])
                                              == mask).all()
    export_mvtec(tmp_path / "set", tmp_path / "exported", progress=False)
    import_mvtec(tmp_path / "exported", tmp_path / "again", val_fraction=0.0, progress=False)
    again = open_dataset(tmp_path / "again").manifest
    assert again["black_level"] == 64 and (read_defect_pixel_map(tmp_path / "again" / again["defect_pixels"])
                                           == mask).all()
    import_mvtec(tmp_path / "cap", tmp_path / "flagged", val_fraction=0.0, progress=False, black_level=0)
    assert "black_level" not in open_dataset(tmp_path / "flagged").manifest  # a flag overrides the folder's
    (tmp_path / "cap" / "defect-pixels.png").unlink()
    with pytest.raises(UserError, match=r"cap/polar_ano\.json: defect_pixels: 'defect-pixels\.png' is not a file"):
        import_mvtec(tmp_path / "cap", tmp_path / "broken", val_fraction=0.0, progress=False)
