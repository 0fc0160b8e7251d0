"""A camera's black level removed before the demosaic (model.priors.black_level): codes mapped with full scale kept,
DoLP read right again, and the level measured from lens-capped frames."""

from __future__ import annotations

import numpy as np
import pytest

from model.priors.api import compute_priors
from model.priors.black_level import DARK_SHARE, check_black_level, measure_black_level, subtract_black_level
from model.priors.mosaic import stokes_to_mosaic


def test_codes_are_mapped_with_full_scale_kept() -> None:
    raw = np.array([[0, 63, 64, 65], [2047, 4094, 4095, 4095]], np.uint16)
    out = subtract_black_level(raw, 64, 12)
    assert out.dtype == np.uint16
    expected = np.clip(np.rint((raw.astype(float) - 64) * 4095 / 4031), 0, 4095)
    assert (out == expected).all()
    assert out[0, :3].tolist() == [0, 0, 0] and out[1, 2] == 4095  # below black: no light; clipped: still full scale
    assert subtract_black_level(raw, 0, 12) is raw  # nothing to do: the frame itself
    raw8 = np.array([[4, 5], [255, 130]], np.uint8)
    assert subtract_black_level(raw8, 4).tolist() == [[0, 1], [255, 128]]


def test_a_pedestal_read_as_light_lowers_dolp_and_removing_it_restores_it() -> None:
    """The physics the station relies on: ``2 b`` added to S0, nothing to S1 and S2."""
    s0 = np.full((32, 32), 0.10)
    truth = 0.30
    ideal = stokes_to_mosaic(s0, truth * s0, 0 * s0)
    raw = np.rint(ideal * 4095 + 64).astype(np.uint16)  # a 64-code pedestal, 1.6 % of full scale
    seen = float(np.median(compute_priors(raw, priors=("dolp",), bit_depth=12)["dolp"]))
    fixed = float(np.median(compute_priors(subtract_black_level(raw, 64, 12), priors=("dolp",), bit_depth=12)["dolp"]))
    assert seen == pytest.approx(truth * 0.10 / (0.10 + 2 * 64 / 4095), abs=0.003)  # 0.228, not 0.30
    assert fixed == pytest.approx(truth, abs=0.003)


@pytest.mark.parametrize("level, bits", [(255, 8), (4095, 12), (-1, 12), (1.5, 12), (True, 8)])
def test_a_level_that_is_not_a_code_below_full_scale_is_refused(level, bits) -> None:
    with pytest.raises(ValueError, match=r"black level .* must be a whole code in \[0, "):
        check_black_level(level, bits)
    raw = np.zeros((4, 4), np.uint8 if bits == 8 else np.uint16)
    if level not in (0, False):
        with pytest.raises(ValueError):
            subtract_black_level(raw, level, bits)


def test_junk_above_the_bit_depth_stays_out_of_range() -> None:
    """Fail closed: a code beyond the stated bits is counted invalid with or without a black level."""
    raw = np.full((4, 4), 2000, np.uint16)
    raw[0, 0] = 60000
    for level in (0, 64):
        priors = compute_priors(subtract_black_level(raw, level, 12), priors=("intensity",), bit_depth=12)
        assert priors.n_out_of_range == 1
    everything = np.arange(4096, dtype=np.uint16).reshape(64, 64)
    assert int(subtract_black_level(everything, 64, 12).max()) == 4095  # in range stays in range


def test_a_float_frame_takes_no_black_level() -> None:
    with pytest.raises(ValueError, match="integer codes"):
        subtract_black_level(np.zeros((4, 4), np.float32), 3)


def test_measured_from_the_lens_capped_frames_only() -> None:
    rng = np.random.default_rng(0)
    dark = [np.clip(np.rint(rng.normal(64, 6, (48, 64))), 0, 4095).astype(np.uint16) for _ in range(5)]
    for d in dark:
        d[7, 9] = 4095  # a hot pixel does not move the median
    lit = [np.full((48, 64), 2000, np.uint16) for _ in range(5)]  # an evenly lit target, in the same folder
    assert measure_black_level(dark + lit, 12) == (64, 5)
    assert measure_black_level(lit, 12) is None
    assert measure_black_level([], 12) is None
    assert DARK_SHARE * 4095 < 2000
    with pytest.raises(ValueError, match="one size and dtype"):
        measure_black_level([dark[0], dark[1][:, :32]], 12)
