"""The numpy priors core: conventions on known answers, round trip, input checks, numerical stability."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from model.priors import IMX250MZR, METHODS, MosaicLayout, compute_priors, stokes_to_mosaic
from model.priors.stokes import aolp, dolp

ALL = ("intensity", "dolp", "aolp", "aolp_cos", "aolp_sin")


def polarized(theta_deg: float, dolp_value: float = 1.0, s0: float = 1.0, shape=(8, 8)):
    t = np.deg2rad(theta_deg)
    full = np.full(shape, s0, np.float32)
    return full, full * dolp_value * np.float32(np.cos(2 * t)), full * dolp_value * np.float32(np.sin(2 * t))


def test_imx250mzr_layout_on_a_hand_written_superpixel():
    # Light polarized at 45 degrees: I0 = I90 = 0.5, I45 = 1, I135 = 0, placed by hand as the IMX250MZR has them:
    # (0,0)=90, (0,1)=45, (1,0)=135, (1,1)=0.
    raw = np.tile(np.array([[0.5, 1.0], [0.0, 0.5]], np.float32), (4, 4))
    p = compute_priors(raw, priors=ALL)
    np.testing.assert_allclose(p["aolp"], np.pi / 4, atol=1e-4)
    np.testing.assert_allclose(p["dolp"], 1.0, atol=1e-6)
    np.testing.assert_allclose(p["intensity"], 0.5, atol=1e-6)
    np.testing.assert_allclose(p["aolp_cos"], 0.0, atol=1e-6)
    np.testing.assert_allclose(p["aolp_sin"], 1.0, atol=1e-6)
    assert IMX250MZR.angles_deg == ((90, 45), (135, 0))


@pytest.mark.parametrize("theta", [0.0, 30.0, 89.0, 91.0, 120.0, 179.0])
@pytest.mark.parametrize("method", sorted(METHODS))
def test_aolp_counts_counter_clockwise_in_0_to_pi(theta, method):
    raw = stokes_to_mosaic(*polarized(theta, dolp_value=0.6))
    p = compute_priors(raw, method=method)
    np.testing.assert_allclose(np.rad2deg(p["aolp"]), theta, atol=0.02)
    np.testing.assert_allclose(p["dolp"], 0.6, atol=1e-5)


def test_round_trip_on_a_smooth_scene_within_stated_error():
    # Stated error of bilinear on smooth content at 12 bits: DoLP RMSE < 0.005, AoLP RMSE < 0.5 degrees.
    h, w = 128, 160
    y, x = np.mgrid[0:h, 0:w].astype(np.float32)
    s0 = 0.6 + 0.3 * np.sin(x / 23) * np.cos(y / 31)
    d = 0.2 + 0.15 * np.cos(y / 19)
    phi = (x + 2 * y) / 90
    s1, s2 = s0 * d * np.cos(2 * phi), s0 * d * np.sin(2 * phi)
    raw = np.rint(stokes_to_mosaic(s0, s1, s2) * 4095).astype(np.uint16)
    p = compute_priors(raw, bit_depth=12)
    c = (slice(2, -2), slice(2, -2))
    assert np.sqrt(np.mean((p["dolp"] - d)[c] ** 2)) < 0.005
    err = np.angle(np.exp(2j * (p["aolp"] - np.mod(phi, np.pi))))[c] / 2
    assert np.degrees(np.sqrt(np.mean(err**2))) < 0.5
    assert np.abs(p["intensity"] - s0 / 2)[c].max() < 0.01


def test_only_requested_priors_and_their_inputs_are_computed():
    raw = np.zeros((4, 4), np.uint8)
    assert set(compute_priors(raw, priors=("intensity",))) == {"intensity", "s0"}
    assert set(compute_priors(raw, priors=("dolp",))) == {"dolp", "s0", "s1", "s2"}
    assert set(compute_priors(raw, priors=("aolp_cos",))) == {"aolp_cos", "aolp_sin", "s0", "s1", "s2"}
    with pytest.raises(ValueError, match="normal"):
        compute_priors(raw, priors=("normal",))


def test_superpixel_is_half_resolution():
    p = compute_priors(np.zeros((6, 10), np.uint8), method="superpixel")
    assert p["dolp"].shape == (3, 5)


def test_bit_depth_scales_codes_to_full_scale_and_counts_junk_bits():
    raw = np.full((4, 4), 4095, np.uint16)
    raw[0, 0] = 65535  # junk above the 12 significant bits
    p = compute_priors(raw, bit_depth=12)
    assert p.n_out_of_range == 1 and p.invalid is not None and p.invalid[0, 0]
    assert p.n_saturated == 16
    np.testing.assert_allclose(p["intensity"], 1.0, atol=1e-6)


def test_nonfinite_float_input_is_reported_not_propagated():
    raw = np.full((8, 8), 0.5, np.float32)
    raw[2, 3], raw[5, 5], raw[0, 1] = np.nan, np.inf, -1e30
    p = compute_priors(raw, priors=ALL)
    assert p.n_nonfinite == 2 and p.n_out_of_range == 1
    assert p.invalid.sum() == 3 and p.invalid[2, 3] and p.invalid[0, 1]
    assert all(np.isfinite(v).all() for v in p.values())


@pytest.mark.parametrize(("raw", "error", "match"), [
    (np.zeros((5, 4), np.uint8), ValueError, r"\(5, 4\)"),
    (np.zeros((4, 4, 3), np.uint8), ValueError, r"\(4, 4, 3\)"),
    (np.zeros((4, 4), np.int32), TypeError, "int32"),
])
def test_bad_mosaics_are_named_in_the_error(raw, error, match):
    with pytest.raises(error, match=match):
        compute_priors(raw)


def test_custom_layout_and_invalid_layout():
    swapped = MosaicLayout("swapped", ((0, 45), (135, 90)))
    raw = stokes_to_mosaic(*polarized(10.0), layout=swapped)
    np.testing.assert_allclose(np.rad2deg(compute_priors(raw, layout=swapped)["aolp"]), 10.0, atol=0.02)
    with pytest.raises(ValueError, match="0, 45, 90 and 135"):
        MosaicLayout("bad", ((0, 45), (90, 90)))
    with pytest.raises(ValueError, match="unknown mosaic layout"):
        compute_priors(raw, layout="nope")


@pytest.mark.parametrize("value", [0, 255])
def test_dark_and_saturated_frames_have_zero_dolp(value):
    p = compute_priors(np.full((8, 8), value, np.uint8), priors=ALL)
    assert (p["dolp"] == 0).all() and (p["aolp"] == 0).all()


def test_dolp_and_aolp_functions_on_edge_values():
    s0 = np.array([0.0, -1.0, 1e-9, 1.0, 1.0], np.float32)
    s1 = np.array([0.0, 0.5, 1e-3, -0.0, -1.0], np.float32)
    s2 = np.array([0.0, 0.5, 0.0, -1e-30, -1e-30], np.float32)
    d, a = dolp(s0, s1, s2), aolp(s1, s2)
    assert np.isfinite(d).all() and ((d >= 0) & (d <= 1)).all()
    assert ((a >= 0) & (a < np.pi)).all()
    assert d[0] == 0 and d[1] == 0  # dark and negative S0: undefined, reported as unpolarized


def _check_priors(p) -> None:
    for key, v in p.items():
        assert v.dtype == np.float32, key
        assert np.isfinite(v).all(), key
    assert ((p["dolp"] >= 0) & (p["dolp"] <= 1)).all()
    assert ((p["aolp"] >= 0) & (p["aolp"] < np.float32(np.pi))).all()
    np.testing.assert_allclose(p["aolp_cos"] ** 2 + p["aolp_sin"] ** 2, 1.0, atol=1e-5)


shapes = st.tuples(st.integers(1, 6), st.integers(1, 6)).map(lambda hw: (2 * hw[0], 2 * hw[1]))


@settings(max_examples=150, deadline=None)
@given(raw=arrays(st.sampled_from([np.uint8, np.uint16]), shapes), method=st.sampled_from(sorted(METHODS)),
       bits=st.sampled_from([None, 8, 10, 12]))
def test_integer_mosaics_never_give_nan_or_out_of_range(raw, method, bits):
    if raw.dtype == np.uint8 and bits is not None:
        bits = min(bits, 8)
    _check_priors(compute_priors(raw, method=method, priors=ALL, bit_depth=bits))


@settings(max_examples=150, deadline=None)
@given(raw=arrays(st.sampled_from([np.float32, np.float64]), shapes,
                  elements=st.floats(allow_nan=True, allow_infinity=True, width=32)),
       method=st.sampled_from(sorted(METHODS)))
def test_float_mosaics_with_nan_inf_and_extremes_never_leak(raw, method):
    p = compute_priors(raw, method=method, priors=ALL)
    _check_priors(p)
    assert p.n_nonfinite == int((~np.isfinite(raw)).sum())


def test_float_input_outside_full_scale_is_counted_and_clipped():
    """A float mosaic is in full-scale units: below 0 or above 1 no sensor reads, so it is out of range."""
    raw = np.full((8, 8), 0.5, np.float32)
    raw[0, 0], raw[3, 4], raw[7, 7] = -0.2, 1.5, 1.0  # 1.0 is full scale, not out of range
    p = compute_priors(raw, priors=ALL)
    assert p.n_out_of_range == 2 and p.invalid.sum() == 2 and p.invalid[0, 0] and p.invalid[3, 4]
    assert 0.0 <= p["intensity"].min() and p["intensity"].max() <= 1.0
