"""The residual-interpolation demosaic: better than bilinear on detail, exact on constant Stokes, stable."""

from __future__ import annotations

import numpy as np
import pytest

from model.priors import IMX250MZR, compute_priors, demosaic, mosaic_to_stokes, stokes_to_mosaic
from model.priors.stokes import intensities_to_stokes
from model.priors.testing import detailed_stokes

ALL = ("intensity", "dolp", "aolp", "aolp_cos", "aolp_sin")
BORDER = 4


def _errors(p, truth) -> tuple[float, float, float]:
    """S0 RMSE, DoLP RMSE, AoLP circular RMSE (rad, where the true DoLP >= 0.1), a 4-px border left out."""
    t0, t1, t2 = (t[BORDER:-BORDER, BORDER:-BORDER] for t in truth)
    crop = {k: v[BORDER:-BORDER, BORDER:-BORDER] for k, v in p.items()}
    t_dolp = np.hypot(t1, t2) / t0
    d_aolp = np.angle(np.exp(1j * (2 * crop["aolp"].astype(np.float64) - np.arctan2(t2, t1)))) / 2
    return (float(np.sqrt(np.mean((crop["s0"] - t0) ** 2))),
            float(np.sqrt(np.mean((crop["dolp"] - t_dolp) ** 2))),
            float(np.sqrt(np.mean(d_aolp[t_dolp >= 0.1] ** 2))))


@pytest.fixture(scope="module")
def noisy_12bit():
    truth = detailed_stokes(192, 256, seed=7)
    mosaic = stokes_to_mosaic(*truth) + np.random.default_rng(7).normal(0, 0.002, truth[0].shape)
    raw = np.clip(np.rint(mosaic * 4095), 0, 4095).astype(np.uint16)
    return raw, truth


def test_residual_beats_bilinear_on_a_detailed_scene(noisy_12bit):
    raw, truth = noisy_12bit
    bil = _errors(compute_priors(raw, method="bilinear", priors=ALL, bit_depth=12), truth)
    res = _errors(compute_priors(raw, method="residual", priors=ALL, bit_depth=12), truth)
    # Measured (this scene): S0 RMSE 0.0279 -> 0.0175, DoLP 0.0436 -> 0.0325, AoLP 6.7 -> 4.4 degrees.
    # A method no better than bilinear fails each line; the bounds ask for about half the measured gains.
    assert res[0] < 0.8 * bil[0]
    assert res[1] < 0.85 * bil[1]
    assert res[2] < 0.8 * bil[2]


def test_residual_keeps_the_samples():
    truth = detailed_stokes(64, 80, seed=3)
    mosaic = stokes_to_mosaic(*truth)
    images = demosaic(mosaic, method="residual")
    for k, angle in enumerate((0, 45, 90, 135)):
        r, c = IMX250MZR.position(angle)
        np.testing.assert_allclose(images[k][r::2, c::2], mosaic[r::2, c::2], atol=2e-6)


@pytest.mark.parametrize("shape", [(2, 2), (4, 6), (32, 48)])
@pytest.mark.parametrize("theta", [0.0, 22.5, 61.0, 135.0, 170.0])
def test_constant_stokes_is_reproduced_exactly(shape, theta):
    s0 = np.full(shape, 0.8, np.float32)
    t = np.deg2rad(theta)
    s1, s2 = s0 * np.float32(0.45 * np.cos(2 * t)), s0 * np.float32(0.45 * np.sin(2 * t))
    p = compute_priors(stokes_to_mosaic(s0, s1, s2), method="residual", priors=ALL)
    np.testing.assert_allclose(p["s0"], 0.8, atol=2e-6)
    np.testing.assert_allclose(p["s1"], s1, atol=2e-6)
    np.testing.assert_allclose(p["s2"], s2, atol=2e-6)
    np.testing.assert_allclose(p["dolp"], 0.45, atol=5e-6)
    np.testing.assert_allclose(np.rad2deg(p["aolp"]), theta, atol=0.02)


def test_direct_stokes_path_equals_the_four_images():
    mosaic = stokes_to_mosaic(*detailed_stokes(64, 96, seed=1))
    direct = mosaic_to_stokes(mosaic, method="residual")
    via_images = intensities_to_stokes(demosaic(mosaic, method="residual"))
    for a, b in zip(direct, via_images, strict=True):
        np.testing.assert_allclose(a, b, atol=2e-6)
    s0_only = mosaic_to_stokes(mosaic, method="residual", polarization=False)
    assert s0_only[1] is None and np.array_equal(s0_only[0], direct[0])


@pytest.mark.parametrize("frame", ["dark", "saturated", "dark_with_hot_pixels", "half_saturated"])
@pytest.mark.parametrize("dtype", [np.uint8, np.uint16])
def test_no_nan_or_inf_on_dark_and_saturated_frames(frame, dtype):
    fs = np.iinfo(dtype).max
    rng = np.random.default_rng(0)
    raw = {
        "dark": np.zeros((24, 32)),
        "saturated": np.full((24, 32), fs),
        "dark_with_hot_pixels": np.where(rng.random((24, 32)) < 0.02, fs, 0),
        "half_saturated": np.where(np.arange(32) < 16, fs, rng.integers(0, 3, (24, 32))),
    }[frame].astype(dtype)
    p = compute_priors(raw, method="residual", priors=ALL)
    for key, value in p.items():
        assert np.isfinite(value).all(), key
    assert ((p["dolp"] >= 0) & (p["dolp"] <= 1)).all()
    if frame in ("dark", "saturated"):
        assert (p["dolp"] == 0).all() and (p["aolp"] == 0).all()


def test_extreme_float_input_stays_finite():
    raw = np.random.default_rng(1).uniform(-1e6, 1e6, (16, 16)).astype(np.float32)
    raw[3, 3] = np.nan
    p = compute_priors(raw, method="residual", priors=ALL)
    assert all(np.isfinite(v).all() for v in p.values())
