"""The station fills a camera's defective pixels before the demosaic: live frames ([camera] defect_pixels), sets that
name a map (station import --defect-pixels), and the map made by station defect-pixels."""

from __future__ import annotations

import json
import time

import cv2
import numpy as np
import pytest

from drivers.frame import Frame
from model.priors import IMX250MZR
from model.priors.defect_pixels import read_defect_pixel_map, write_defect_pixel_map
from model.priors.mosaic import stokes_to_mosaic
from station.assembly import defect_pixel_map
from station.config import ConfigError, parse_config
from station.errors import UserError
from station.inspector import Inference, Inspector


class MeanDetector:
    """Scores a frame by its brightest DoLP: a stuck pixel reads as polarized light."""

    model_id, threshold, priors = "test-dolp", 0.5, ("dolp",)

    def infer(self, priors):
        return Inference(float(np.max(priors["dolp"])))


def _frame(raw: np.ndarray) -> Frame:
    return Frame(raw, "Mono16", 12, 1, 0, time.time_ns())


def _scene(h: int = 48, w: int = 64) -> np.ndarray:
    s0 = np.full((h, w), 0.3)
    return np.rint(stokes_to_mosaic(s0, 0.02 * s0, 0 * s0) * 4095).astype(np.uint16)


def test_the_inspector_fills_the_map_and_rejects_a_map_of_another_size() -> None:
    raw = _scene()
    hot = raw.copy()
    mask = np.zeros(raw.shape, bool)
    mask[[10, 30], [21, 40]] = True
    hot[mask] = 4095
    plain = Inspector(MeanDetector(), IMX250MZR).inspect(_frame(hot))
    filled = Inspector(MeanDetector(), IMX250MZR, defect_pixels=mask).inspect(_frame(hot))
    clean = Inspector(MeanDetector(), IMX250MZR).inspect(_frame(raw))
    assert plain.score > 0.5 > filled.score and filled.score == pytest.approx(clean.score, abs=0.01)
    wrong = Inspector(MeanDetector(), IMX250MZR, defect_pixels=mask[:, :32]).inspect(_frame(hot))
    assert wrong.score is None and "one region of interest" in wrong.error  # not judged: rejected with the reason


def test_a_map_the_config_names_is_read_or_named_in_one_line(tmp_path) -> None:
    mask = np.zeros((48, 64), bool)
    mask[3, 4] = True
    write_defect_pixel_map(tmp_path / "map.png", mask)
    cfg = parse_config(f'[camera]\ndefect_pixels = "{tmp_path / "map.png"}"\n', source="s.toml")
    assert (defect_pixel_map(cfg) == mask).all() and defect_pixel_map(cfg, second=True) is None
    cfg = parse_config(f'[second_camera]\ndefect_pixels = "{tmp_path / "none.png"}"\n', source="s.toml")
    with pytest.raises(ConfigError, match=r"^s\.toml: \[second_camera\] defect_pixels: .*none\.png: no such file$"):
        defect_pixel_map(cfg, second=True)


def test_import_copies_the_map_and_the_set_s_priors_are_filled(tmp_path) -> None:
    """A captured folder imported with its camera's map: the set holds a copy and names it, and the priors every
    command reads from it are the frames' with those pixels filled."""
    from station.datasets import load_split, set_defect_pixels
    from station.mvtec import import_mvtec

    src = tmp_path / "captured"
    (src / "train" / "good").mkdir(parents=True)
    raw = _scene(64, 64)
    mask = np.zeros(raw.shape, bool)
    mask[[10, 40], [21, 33]] = True
    for k in range(4):
        cv2.imwrite(str(src / "train" / "good" / f"{k:03d}.png"), np.where(mask, 4095, raw).astype(np.uint16))
    write_defect_pixel_map(tmp_path / "map.png", mask)
    import_mvtec(src, tmp_path / "set", bit_depth=12, val_fraction=0.0, progress=False,
                 defect_pixels=tmp_path / "map.png")
    manifest = json.loads((tmp_path / "set" / "manifest.json").read_text())
    assert (read_defect_pixel_map(tmp_path / "set" / manifest["defect_pixels"]) == mask).all()
    assert (set_defect_pixels(tmp_path / "set", manifest) == mask).all()
    sp = load_split(tmp_path / "set", "train", ("dolp",), 64, progress=False)
    assert float(sp.priors.max()) < 0.1  # 2 % DoLP everywhere; a stuck pixel would read near 1
    with pytest.raises(UserError, match=r"8x8 map for 64x64 frames: a map is made for one region of interest"):
        import_mvtec(src, tmp_path / "set2", bit_depth=12, val_fraction=0.0, progress=False,
                     defect_pixels=_small_map(tmp_path))
    write_defect_pixel_map(tmp_path / "set" / manifest["defect_pixels"], np.zeros((8, 8), bool))
    with pytest.raises(UserError, match=r"set/manifest\.json: defect_pixels: a 8x8 map for the set's 64x64 frames"):
        load_split(tmp_path / "set", "train", ("dolp",), 64, progress=False)  # one line, not a traceback per sample
    (tmp_path / "set" / manifest["defect_pixels"]).write_text("broken")
    with pytest.raises(UserError, match=r"set/manifest\.json: defect_pixels: .*not a single-channel PNG"):
        set_defect_pixels(tmp_path / "set", manifest)


def _small_map(tmp_path):
    write_defect_pixel_map(tmp_path / "small.png", np.zeros((8, 8), bool))
    return tmp_path / "small.png"


def test_the_command_writes_the_map_from_dark_frames(tmp_path, capsys) -> None:
    from station.cli import main

    rng = np.random.default_rng(1)
    (tmp_path / "dark").mkdir()
    for k in range(6):
        dark = np.clip(rng.normal(64, 8, (96, 128)), 0, 4095).astype(np.uint16)
        dark[50, 61] = 4095
        cv2.imwrite(str(tmp_path / "dark" / f"{k}.png"), dark)
    assert main(["defect-pixels", "--frames", str(tmp_path / "dark"), "--bit-depth", "12",
                 "--out", str(tmp_path / "map.png")]) == 0
    assert "1 defective pixels in 6 frames of 128x96: (x, y) (61, 50)" in capsys.readouterr().out
    assert read_defect_pixel_map(tmp_path / "map.png").nonzero() == (np.array([50]), np.array([61]))
    assert main(["defect-pixels", "--frames", str(tmp_path / "none"), "--out", str(tmp_path / "m.png")]) == 2
    assert "no PNG files" in capsys.readouterr().err
