"""Sensor model statistics: noise variance against signal, bit depth, saturation, polarizer, determinism."""

from __future__ import annotations

import dataclasses

import cv2
import numpy as np
import pytest

from model.priors.conventions import IMX250MZR
from sim.errors import SimError
from sim.sensor import FULL_SCALE_S0, SensorConfig, digitize, simulate, suppress_fireflies


def flat(value: float, shape=(200, 200)) -> np.ndarray:
    return np.full(shape, value, dtype=np.float32)


@pytest.mark.parametrize("level", [0.05, 0.3, 0.8])
def test_noise_variance_is_shot_plus_read(level: float) -> None:
    cfg = SensorConfig(bit_depth=16, full_well_e=10000.0, read_noise_e=5.0)
    raw = digitize(flat(level), cfg, np.random.default_rng(1))
    electrons = raw.astype(np.float64) * cfg.full_scale_e / cfg.max_code
    expected_var = level * cfg.full_scale_e + cfg.read_noise_e**2  # Poisson + Gaussian
    assert electrons.mean() == pytest.approx(level * cfg.full_scale_e, rel=0.01)
    assert electrons.var() == pytest.approx(expected_var, rel=0.05)


def test_noise_off_gives_exact_codes() -> None:
    cfg = SensorConfig(bit_depth=12, shot_noise=False, read_noise_e=0.0)
    raw = digitize(flat(0.5, (4, 4)), cfg, np.random.default_rng(0))
    assert raw.dtype == np.uint16 and np.all(raw == round(0.5 * 4095))


@pytest.mark.parametrize(("bits", "dtype"), [(8, np.uint8), (12, np.uint16), (16, np.uint16)])
def test_bit_depth_and_saturation(bits: int, dtype: type) -> None:
    cfg = SensorConfig(bit_depth=bits)
    raw = digitize(flat(3.0, (8, 8)), cfg, np.random.default_rng(0))  # 3x over full scale
    assert raw.dtype == dtype
    assert np.all(raw == 2**bits - 1)  # clipped at the full well, never wrapped
    dark = digitize(flat(0.0, (8, 8)), SensorConfig(bit_depth=bits, read_noise_e=0.0), np.random.default_rng(0))
    assert np.all(dark == 0)


def test_full_well_clips_before_adc_with_gain() -> None:
    # analog gain 2: full scale is reached at half the well, and the ADC clips there
    cfg = SensorConfig(bit_depth=12, analog_gain=2.0, shot_noise=False, read_noise_e=0.0)
    assert cfg.full_scale_e == cfg.full_well_e / 2
    assert digitize(flat(0.25, (2, 2)), cfg, np.random.default_rng(0))[0, 0] == round(0.25 * 4095)
    assert digitize(flat(1.5, (2, 2)), cfg, np.random.default_rng(0))[0, 0] == 4095


def test_mosaic_layout_and_extinction_ratio() -> None:
    # fully polarized at 0 degrees (S1 = S0): only the 0-degree pixel sees light, the 90-degree one none
    s0 = flat(0.4, (4, 4))
    cfg = SensorConfig(bit_depth=16, exposure_gain=1.0, shot_noise=False, read_noise_e=0.0)
    frame = simulate(s0, s0, 0 * s0, cfg, np.random.default_rng(0))
    r0, c0 = IMX250MZR.position(0)
    r90, c90 = IMX250MZR.position(90)
    assert frame.ideal[r0, c0] == pytest.approx(0.4)
    assert frame.ideal[r90, c90] == pytest.approx(0.0, abs=1e-7)
    leaky = simulate(s0, s0, 0 * s0, SensorConfig(bit_depth=16, exposure_gain=1.0, extinction_ratio=100.0,
                                                   shot_noise=False, read_noise_e=0.0), np.random.default_rng(0))
    # an extinction ratio of 100 leaks 1/101 of the light through the crossed polarizer
    assert leaky.ideal[r90, c90] == pytest.approx(0.4 / 101, rel=1e-4)
    assert leaky.ideal[r0, c0] / leaky.ideal[r90, c90] == pytest.approx(100.0, rel=1e-3)
    np.testing.assert_array_equal(leaky.s1, frame.s1)  # ground truth is the scene, not the imperfect filter


def test_same_seed_same_raw_and_exposure_scaling() -> None:
    s = np.random.default_rng(3).uniform(0, 0.3, (3, 16, 16)).astype(np.float32)
    cfg = SensorConfig(exposure_gain=2.0)
    a = simulate(s[0], 0.1 * s[1], 0.1 * s[2], cfg, np.random.default_rng(7))
    b = simulate(s[0], 0.1 * s[1], 0.1 * s[2], cfg, np.random.default_rng(7))
    np.testing.assert_array_equal(a.raw, b.raw)
    np.testing.assert_allclose(a.s0, 2.0 * s[0], rtol=1e-6)


def test_bad_config_and_shapes_are_clear_errors() -> None:
    with pytest.raises(SimError, match="bit_depth"):
        SensorConfig(bit_depth=9)
    with pytest.raises(SimError, match="extinction_ratio"):
        SensorConfig(extinction_ratio=0.5)
    with pytest.raises(SimError, match="even sides"):
        simulate(flat(0.1, (3, 4)), flat(0, (3, 4)), flat(0, (3, 4)), SensorConfig(), np.random.default_rng(0))


def test_lens_blur_softens_the_light_before_the_polarizers_and_keeps_the_truth_sharp() -> None:
    """``lens_blur_px``: a Gaussian point spread on S0, S1, S2 before the polarizer array. 0 is the sharp render
    (byte-identical raw); above 0 the noiseless mosaic's polarization across a sharp edge between horizontally and
    vertically polarized halves is softened (no longer +-S0 next to the edge) and unchanged far from it; the
    ground-truth Stokes stay the scene's (sharp); a negative sigma is refused."""
    h, w = 16, 32
    s0 = np.full((h, w), 0.5, np.float32)
    s1 = np.where(np.arange(w) < w // 2, 0.5, -0.5).astype(np.float32) * np.ones((h, 1), np.float32)
    s2 = np.zeros((h, w), np.float32)
    sharp = SensorConfig(exposure_gain=1.0, shot_noise=False, read_noise_e=0.0)
    soft = SensorConfig(exposure_gain=1.0, shot_noise=False, read_noise_e=0.0, lens_blur_px=1.5)
    a = simulate(s0, s1, s2, sharp, np.random.default_rng(0))
    z = simulate(s0, s1, s2, SensorConfig(exposure_gain=1.0, shot_noise=False, read_noise_e=0.0, lens_blur_px=0.0),
                 np.random.default_rng(0))
    np.testing.assert_array_equal(a.raw, z.raw)
    b = simulate(s0, s1, s2, soft, np.random.default_rng(0))
    np.testing.assert_array_equal(b.s1, a.s1)  # the truth is the scene's
    # each 2x2 cell's 0 and 90 deg pixels: their difference is the cell's S1 as the sensor sees it
    def cell_s1(m: np.ndarray) -> np.ndarray:
        r0, c0 = IMX250MZR.position(0)
        r90, c90 = IMX250MZR.position(90)
        return m[r0::2, c0::2] - m[r90::2, c90::2]
    sa, sb = cell_s1(a.ideal), cell_s1(b.ideal)
    edge = w // 4 - 1  # the cell left of the edge
    assert sa[:, edge] == pytest.approx(0.5) and sa[:, edge + 1] == pytest.approx(-0.5)
    assert 0.05 < sb[h // 4, edge] < 0.45 and -0.45 < sb[h // 4, edge + 1] < -0.05
    far = np.r_[0:w // 2 - 7, w // 2 + 7:w]  # more than 4 sigma from the edge, the image is as sharp
    np.testing.assert_allclose(b.ideal[:, far], a.ideal[:, far], atol=1e-4)
    with pytest.raises(SimError, match="lens_blur_px"):
        SensorConfig(lens_blur_px=-0.5)


def test_vignetting_darkens_the_corners_by_its_share_and_keeps_the_truth() -> None:
    """``vignetting``: cos^4 relative illumination, 1 at the centre and ``1 - vignetting`` at the corners, on the
    light before the polarizers (so DoLP is unchanged); the ground truth is the scene's; outside [0, 1) refused."""
    from sim.sensor import relative_illumination

    fall = relative_illumination(48, 64, 0.2)
    assert fall[0, 0] == pytest.approx(0.8, abs=1e-6) and fall[-1, -1] == pytest.approx(0.8, abs=1e-6)
    assert fall.max() <= 1.0 and fall[23:25, 31:33].min() > 0.999 and (relative_illumination(4, 4, 0.0) == 1).all()
    s0 = np.full((48, 64), 0.5, np.float32)
    s1, s2 = 0.3 * s0, np.zeros_like(s0)
    quiet = {"exposure_gain": 1.0, "shot_noise": False, "read_noise_e": 0.0}
    a = simulate(s0, s1, s2, SensorConfig(**quiet), np.random.default_rng(0))
    b = simulate(s0, s1, s2, SensorConfig(**quiet, vignetting=0.2), np.random.default_rng(0))
    np.testing.assert_array_equal(b.s0, a.s0)
    np.testing.assert_allclose(b.ideal, a.ideal * fall, rtol=1e-5)
    for bad in (-0.1, 1.0):
        with pytest.raises(SimError, match="vignetting"):
            SensorConfig(vignetting=bad)


def test_a_lens_blur_does_not_spread_a_renders_firefly_into_a_clipped_spot_but_keeps_a_highlight() -> None:
    """A firefly (one Monte Carlo sample that found a light: one pixel at S0 = 300 beside 0.6, where the sensor clips
    at 2) clips to one pixel on a sharp sensor; blurred as it was rendered it became a patch of clipped pixels, a
    bright spot that raised good parts over the shipped threshold. It is brought to full scale before the blur, its
    polarization kept. A highlight (a bright patch, also one rendered noisily) still clips after the blur; a sharp
    exposure still clips the firefly to its one pixel."""
    h, w = 32, 32
    s0 = np.full((h, w), 0.6, np.float32)
    s0[10, 10] = 300.0  # a firefly
    s0[20:27, 20:27] = 6.0  # a highlight
    s0[4:11, 20:27] = np.where(np.indices((7, 7)).sum(0) % 2, 20.0, 1.0)  # a highlight rendered noisily
    s1, s2 = 0.3 * s0, -0.2 * s0
    cfg = SensorConfig(bit_depth=12, exposure_gain=1.0, shot_noise=False, read_noise_e=0.0, lens_blur_px=0.7)
    raw = simulate(s0, s1, s2, cfg, np.random.default_rng(0)).raw
    full = 2**12 - 1
    assert (raw[6:15, 6:15] < full).all()  # no clipped spot around the firefly
    assert (raw[22:25, 22:25] == full).all()  # the highlight's middle still clips
    f0, f1, f2 = suppress_fireflies(s0, s1, s2)
    assert f0[10, 10] == pytest.approx(FULL_SCALE_S0) and f1[10, 10] / f0[10, 10] == pytest.approx(0.3)
    assert f2[10, 10] / f0[10, 10] == pytest.approx(-0.2)
    np.testing.assert_array_equal(f0[20:27, 20:27], s0[20:27, 20:27])  # a patch is no firefly
    np.testing.assert_array_equal(f0[4:11, 20:27], s0[4:11, 20:27])  # nor are a noisy patch's bright pixels
    assert (raw[6:9, 22:25] == full).all()  # which clip after the blur as the light they average does
    sharp = dataclasses.replace(cfg, lens_blur_px=0.0)
    spread = cv2.GaussianBlur(s0, (0, 0), 0.7)  # what the blur made of it before: a clipped spot
    assert spread[9:12, 9:12].min() > FULL_SCALE_S0
    a = simulate(s0, s1, s2, sharp, np.random.default_rng(0))
    assert a.raw[10, 10] == full and a.n_saturated > 0  # the sharp sensor clips the firefly to its one pixel
