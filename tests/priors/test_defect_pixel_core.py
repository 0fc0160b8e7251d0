"""Defective sensor pixels: found in frames with the lens capped, filled from neighbours of the same polarizer angle."""

from __future__ import annotations

import numpy as np
import pytest

from model.priors.api import compute_priors
from model.priors.defect_pixels import (
    fill_defect_pixels,
    find_defect_pixels,
    read_defect_pixel_map,
    write_defect_pixel_map,
)
from model.priors.mosaic import stokes_to_mosaic


def _mosaic(h: int = 48, w: int = 64) -> np.ndarray:
    """A smooth polarized scene as a 12-bit mosaic (codes in uint16)."""
    y, x = np.mgrid[0:h, 0:w] / 64.0
    s0 = 0.4 + 0.2 * x
    s1, s2 = 0.1 * s0 * np.cos(3 * y), 0.1 * s0 * np.sin(3 * y)
    return np.rint(stokes_to_mosaic(s0, s1, s2) * 4095).astype(np.uint16)


def test_a_stuck_pixel_is_filled_from_its_own_angle() -> None:
    raw = _mosaic()
    hot = raw.copy()
    mask = np.zeros(raw.shape, bool)
    for y, x in ((10, 11), (0, 0), (47, 63), (20, 30), (20, 32)):  # corners and two neighbours of one angle
        hot[y, x] = 4095
        mask[y, x] = True
    filled = fill_defect_pixels(hot, mask)
    assert filled.dtype == raw.dtype and not np.shares_memory(filled, hot)
    assert np.abs(filled.astype(int) - raw)[mask].max() <= 60  # a smooth scene: its angle's neighbours' mean
    assert (filled[~mask] == hot[~mask]).all()
    clean, fixed = compute_priors(raw, bit_depth=12), compute_priors(filled, bit_depth=12)
    broken = compute_priors(hot, bit_depth=12)
    assert np.abs(fixed["dolp"] - clean["dolp"]).max() < 0.02 < np.abs(broken["dolp"] - clean["dolp"]).max()


def test_a_cluster_and_an_empty_map() -> None:
    raw = _mosaic()
    mask = np.zeros(raw.shape, bool)
    mask[10:22, 10:22] = True  # wider than a pixel's same-angle neighbours reach in one pass
    filled = fill_defect_pixels(np.where(mask, 0, raw).astype(raw.dtype), mask)
    assert filled[mask].min() > 0 and np.isfinite(filled).all()
    assert fill_defect_pixels(raw, np.zeros(raw.shape, bool)) is raw and fill_defect_pixels(raw, None) is raw
    with pytest.raises(ValueError, match=r"64x48.*one region of interest"):
        fill_defect_pixels(raw[:, :32], np.zeros(raw.shape, bool))


def test_dark_frames_find_the_stuck_pixels_and_nothing_else() -> None:
    rng = np.random.default_rng(0)
    stuck = np.zeros((96, 128), bool)
    stuck[[3, 17, 30, 90], [5, 120, 31, 2]] = True
    frames = []
    for _ in range(9):
        dark = rng.normal(64, 8, (96, 128))  # black level and read noise, 12-bit codes
        frames.append(np.clip(np.where(stuck, 4095, dark), 0, 4095).astype(np.uint16))
    found = find_defect_pixels(frames, bit_depth=12, min_step=0.05)
    assert (found == stuck).all()
    with pytest.raises(ValueError, match="frames of one size"):
        find_defect_pixels([frames[0], frames[1][:, :64]])


def test_a_scene_is_not_a_sensor_s_defects() -> None:
    """Frames with fine detail that stays put (a checkerboard of 1 px) are refused, not mapped."""
    board = (np.indices((48, 64)).sum(0) % 3 == 0) * 3000 + 500
    with pytest.raises(ValueError, match="lens capped"):
        find_defect_pixels([board.astype(np.uint16)] * 3, bit_depth=12)


def test_the_map_round_trips_and_names_a_bad_file(tmp_path) -> None:
    mask = np.zeros((48, 64), bool)
    mask[1, 2] = True
    write_defect_pixel_map(tmp_path / "map.png", mask)
    assert (read_defect_pixel_map(tmp_path / "map.png") == mask).all()
    (tmp_path / "bad.png").write_text("not an image")
    with pytest.raises(ValueError, match=r"bad\.png: not a single-channel PNG"):
        read_defect_pixel_map(tmp_path / "bad.png")
    with pytest.raises(ValueError, match=r"none\.png: no such file"):
        read_defect_pixel_map(tmp_path / "none.png")


def test_a_lit_target_finds_the_pixels_stuck_dark() -> None:
    """Dark frames cannot show a pixel stuck at 0; frames of an evenly lit plain target (here partly polarized:
    each angle its own level) do, from its own angle's neighbours."""
    rng = np.random.default_rng(2)
    dead = np.zeros((96, 128), bool)
    dead[[7, 50, 88], [9, 64, 127]] = True
    level = np.tile(np.array([[1900, 2100], [2000, 2200]]), (48, 64))  # four angles, four levels
    frames = [np.clip(np.where(dead, 0, level + rng.normal(0, 30, level.shape)), 0, 4095).astype(np.uint16)
              for _ in range(5)]
    assert (find_defect_pixels(frames, bit_depth=12) == dead).all()
