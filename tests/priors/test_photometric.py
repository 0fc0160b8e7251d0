"""Photometric stereo priors (``model.priors.photometric``, ``compute_set_priors``): a frame per dome segment."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from model.priors import compute_priors
from model.priors.api import compute_set_priors
from model.priors.mosaic import stokes_to_mosaic
from model.priors.photometric import check_tilts, segment_index, tilt
from model.priors.testing import detailed_stokes


def test_tilt_is_the_normalised_difference_signed_toward_the_first_frame_and_safe_where_dark() -> None:
    a = np.array([0.6, 0.2, 0.0, np.nan, np.inf, 1e-9], np.float32)
    b = np.array([0.2, 0.6, 0.0, 0.5, 0.5, 1e-9], np.float32)
    t = tilt(a, b)
    assert t[0] == pytest.approx(0.5) and t[1] == pytest.approx(-0.5)
    assert t[2:].tolist() == [0.0, 0.0, 0.0, 0.0]  # dark or not finite: 0, never NaN
    assert t.dtype == np.float32


def test_tilt_divides_out_albedo_and_exposure() -> None:
    rng = np.random.default_rng(0)
    shade_a, shade_b = rng.uniform(0.2, 1.0, (2, 16, 16)).astype(np.float32)
    albedo = rng.uniform(0.05, 1.0, (16, 16)).astype(np.float32)
    assert np.allclose(tilt(albedo * shade_a, albedo * shade_b), tilt(3 * shade_a, 3 * shade_b), atol=1e-5)


def test_segments_match_modulo_360_and_a_missing_pair_is_named() -> None:
    assert segment_index((0.0, 180.0), 360.0) == 0 and segment_index((0.0, 180.0), 90.0) is None
    check_tilts(("intensity", "tilt_x"), (180.0, 0.0))
    with pytest.raises(ValueError, match="tilt_y needs frames at 90 and 270 deg; there is a frame per dome segment"):
        check_tilts(("tilt_y",), (0.0, 180.0))
    with pytest.raises(ValueError, match="there is one frame per part"):
        compute_priors(np.zeros((8, 8), np.uint8), priors=("tilt_x",))


def test_set_priors_read_intensity_and_polarization_from_the_frames_mean_and_tilt_from_the_pair() -> None:
    s0, s1, s2 = detailed_stokes(32, 48)
    lean = np.linspace(-0.4, 0.4, 48, dtype=np.float32)[None, :]  # a face tilting along x
    lit_x = stokes_to_mosaic(s0 * (1 + lean), s1 * (1 + lean), s2 * (1 + lean)) * 0.5
    lit_minus_x = stokes_to_mosaic(s0 * (1 - lean), s1 * (1 - lean), s2 * (1 - lean)) * 0.5
    uniform = stokes_to_mosaic(s0, s1, s2) * 0.5
    names = ("intensity", "dolp", "aolp", "tilt_x")
    got = compute_set_priors([lit_x, lit_minus_x], (0.0, 180.0), priors=names)
    one = compute_priors(uniform, priors=names[:3])
    for n in names[:3]:
        assert np.allclose(got[n], one[n], atol=1e-5), n
    inner = got["tilt_x"][4:-4, 4:-4]  # away from the demosaic's border
    assert np.allclose(inner, np.broadcast_to(lean, got["tilt_x"].shape)[4:-4, 4:-4], atol=0.02)
    # the frames in the other order: the same uniform priors, the tilt still toward +x
    swapped = compute_set_priors([lit_minus_x, lit_x], (180.0, 0.0), priors=names)
    assert np.array_equal(swapped["tilt_x"], got["tilt_x"]) and np.allclose(swapped["intensity"], got["intensity"])


def test_set_priors_never_leave_nan_and_report_the_worst_frame() -> None:
    good = np.full((16, 16), 0.5, np.float32)
    bad = good.copy()
    bad[:4, :] = np.nan
    bad[4:6, :] = 7.0  # out of range
    p = compute_set_priors([good, bad], (0.0, 180.0), priors=("intensity", "dolp", "aolp", "tilt_x"))
    assert all(np.isfinite(v).all() for v in p.values())
    assert p.n_nonfinite == 64 and p.n_out_of_range == 32 and p.invalid is not None and p.invalid.sum() == 96
    with pytest.raises(ValueError, match="3 frames for 2 dome segments"):
        compute_set_priors([good, good, good], (0.0, 180.0))


def test_frame_motion_reads_a_shift_across_opposite_light_and_is_finite_on_anything() -> None:
    from model.priors.photometric import frame_motion

    rng = np.random.default_rng(0)
    texture = cv2.GaussianBlur(rng.random((240, 320)).astype(np.float32), (0, 0), 2.0) + 0.5
    ramp = np.linspace(0.3, 1.0, 320, dtype=np.float32)[None, :]  # lit from +x, then from -x
    a, b = texture * ramp, texture * ramp[:, ::-1]
    assert frame_motion(a, b) < 0.2
    assert frame_motion(a, np.roll(b, 1, axis=1)) == pytest.approx(1.0, abs=0.2)
    assert frame_motion(a, np.roll(b, (3, -2), axis=(0, 1))) == pytest.approx(np.hypot(3, 2), abs=0.3)
    # a frame wider than MOTION_WIDTH_PX is compared smaller, the answer in its own pixels
    big = cv2.resize(a, None, fx=4, fy=4, interpolation=cv2.INTER_CUBIC)
    assert frame_motion(big, np.roll(big, 4, axis=1)) == pytest.approx(4.0, abs=0.8)
    for x, y in ((a, np.zeros_like(a)), (np.full_like(a, np.nan), a), (a, np.full_like(a, np.inf)), (a, a[:100])):
        assert frame_motion(x, y) == 0.0
