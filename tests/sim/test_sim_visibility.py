"""The detectability oracle (sim/visibility.py, sim/oracle.py): analytic sensor noise against Monte Carlo, the SNR of
a defect of known size and material, out-of-view defects, what the paired render changes, render windows."""

from __future__ import annotations

import copy
from dataclasses import replace

import cv2
import numpy as np
import pytest

from sim.dataset import oracle_record
from sim.defects import DefectConfig, apply_defect
from sim.meshes import usb_brick
from sim.oracle import RenderOutput, defect_snr, defect_window, snr_from_pairs
from sim.render import RenderSettings, render_sample
from sim.scene import SceneConfig, object_to_world, sample_scene
from sim.sensor import SensorConfig, digitize, ideal_mosaic, raw_to_fullscale
from sim.variant import set_variant
from sim.visibility import prior_std, prior_values

SMALL = {"width": 128, "height": 96}


@pytest.mark.parametrize("bits", [8, 12])
@pytest.mark.parametrize("stokes", [(0.6, 0.12, -0.05), (0.2, 0.0, 0.03), (1.2, -0.3, 0.2)])
def test_analytic_prior_std_matches_monte_carlo(bits: int, stokes: tuple[float, float, float]) -> None:
    """2 x std of a 2x2 superpixel's priors over sensor noise draws (sim.sensor.digitize) = prior_std, within 8 %."""
    cfg = SensorConfig(bit_depth=bits)
    s = [np.full((400, 400), v, np.float32) for v in stokes]
    raw = digitize(ideal_mosaic(*s, cfg), cfg, np.random.default_rng(0))
    m = raw_to_fullscale(raw, cfg).astype(np.float64)
    i0, i45, i90, i135 = m[1::2, 1::2], m[0::2, 1::2], m[0::2, 0::2], m[1::2, 0::2]  # IMX250MZR: (1,1)=0 ... (0,0)=90
    s0, s1, s2 = (i0 + i45 + i90 + i135) / 2, i0 - i90, i45 - i135
    noisy = prior_values(s0, s1, s2)
    want = {k: float(v.ravel()[0]) for k, v in prior_std(*(np.array([x]) for x in stokes), cfg).items()}
    got = {"intensity": noisy["intensity"].std(), "dolp": noisy["dolp"].std(),
           "aolp": np.std(np.angle(np.exp(2j * (noisy["aolp"] - noisy["aolp"].mean()))) / 2)}
    for k, v in got.items():
        assert 2 * v == pytest.approx(want[k], rel=0.08), k


def _output(s0: np.ndarray) -> RenderOutput:
    z = np.zeros_like(s0)
    return RenderOutput(s0, z, z.copy())


def test_uniform_disc_snr_is_sqrt_pixels_times_contrast_over_noise() -> None:
    """A darker disc on an unpolarized field: intensity SNR = sqrt(N) * dI / std, std from the shot/read/ADC model."""
    cfg = SensorConfig()
    yy, xx = np.mgrid[:64, :64]
    mask = (yy - 32) ** 2 + (xx - 32) ** 2 < 10**2
    good = np.full((64, 64), 0.2, np.float32)  # radiance: exposed S0 = 0.4, each polarizer reads 0.2 full scale
    bad = np.where(mask, 0.15, 0.2).astype(np.float32)
    snr, dem = snr_from_pairs([(_output(bad), _output(good))], mask, cfg)

    def var(i: float) -> float:
        return i / cfg.full_scale_e + (cfg.read_noise_e / cfg.full_scale_e) ** 2 + 1 / (12 * 255**2)

    want = np.sqrt(mask.sum()) * 0.1 / 2 / np.sqrt(0.5 * (var(0.2) + var(0.15)))
    assert snr["intensity"] == pytest.approx(want, rel=1e-3)
    assert snr["dolp"] == pytest.approx(0, abs=1e-6) and snr["aolp"] == pytest.approx(0, abs=1e-6)
    assert 0.9 * want < dem["intensity"] < want  # the demosaic blurs the disc's 1-px rim: a few % lost


@pytest.fixture(scope="module")
def scene_case():
    set_variant()
    model = usb_brick()
    cfg = SceneConfig(focal_length_mm=150.0, camera_target_jitter_m=0.0, camera_polar_deg=(20.0, 30.0),
                      rest_pose=0, ambient_radiance=0.0)
    params = sample_scene(np.random.default_rng(5), cfg, model)
    to_world = object_to_world(params["pose"])
    cam_obj = np.linalg.solve(to_world, np.r_[params["camera"]["origin"], 1.0])[:3]
    return model, params, cam_obj


def test_a_diffuse_stain_gives_the_expected_intensity_snr(scene_case) -> None:
    """A stain of known darkening k on a Lambertian body scales the radiance inside it by k, so its expected SNR
    follows from the good render alone: sqrt(sum_mask ((1 - k) I / std)^2). Within 10 % (render noise, the
    window's pixel jitter)."""
    model, params, cam_obj = scene_case
    diffuse = replace(model, materials={k: {"type": "diffuse", "finish": "rough"} for k in model.materials})
    params = copy.deepcopy(params)
    for key, m in params["materials"].items():
        params["materials"][key] = {"type": "diffuse", "colour": m["colour"], "finish": "rough"}
    k = 0.5
    defect = apply_defect(diffuse, "stain", np.random.default_rng(1),
                          DefectConfig(stain_radius_mm=(3.0, 3.0), stain_darken=(k, k)), cam_obj, params["materials"])
    cfg = SensorConfig()
    settings = RenderSettings(**SMALL, spp=4)
    result, mask = defect_snr(diffuse, params, defect, settings, 3, cfg)
    assert result.pixels == mask.sum() > 30
    good = render_sample(diffuse, params, None, RenderSettings(**SMALL, spp=16, ground_truth=False), 3)
    i = (good.s0 * cfg.exposure_gain / 2)[mask].astype(np.float64)

    def var(x: np.ndarray) -> np.ndarray:
        return x / cfg.full_scale_e + (cfg.read_noise_e / cfg.full_scale_e) ** 2 + 1 / (12 * 255**2)

    want = np.sqrt(np.sum(((1 - k) * i) ** 2 / (0.5 * (var(i) + var(k * i)))))
    assert result.snr["intensity"] == pytest.approx(want, rel=0.10)
    assert result.best == "intensity" and result.snr["dolp"] < 0.1 * want  # Mitsuba's diffuse does not polarize


def test_an_out_of_view_defect_has_snr_0_and_label_0(scene_case) -> None:
    model, params, cam_obj = scene_case
    defect = apply_defect(model, "dent", np.random.default_rng(1), DefectConfig(), cam_obj, params["materials"])
    away = copy.deepcopy(params)
    o, t = np.array(params["camera"]["origin"]), np.array(params["camera"]["target"])
    away["camera"]["target"] = (2 * o - t).tolist()
    result, mask = defect_snr(model, away, defect, RenderSettings(**SMALL, spp=4), 3, SensorConfig())
    assert not mask.any() and result.pixels == 0 and result.best_snr == 0
    assert all(v == 0 for v in result.snr.values()) and all(v == 0 for v in result.snr_demosaic.values())
    assert oracle_record(result)["snr"] == {"intensity": 0, "dolp": 0, "aolp": 0, "normal": 0}
    # the sample's label comes from the same (empty) mask
    label = int(render_sample(model, away, defect, RenderSettings(**SMALL, spp=1, ground_truth=False), 3)
                .defect_mask.any())
    assert label == 0


def test_the_paired_render_differs_only_around_the_defect(scene_case) -> None:
    """Same camera, light, materials and seed: the two renders agree except on the defect and next to it."""
    model, params, cam_obj = scene_case
    defect = apply_defect(model, "dent", np.random.default_rng(1),
                          DefectConfig(dent_radius_mm=(2.5, 3.0), dent_depth_mm=(0.4, 0.5)), cam_obj,
                          params["materials"])
    settings = RenderSettings(**SMALL, spp=4)
    bad = render_sample(model, params, defect, settings, 11)
    good = render_sample(model, params, None, settings, 11)
    mask = bad.defect_mask
    assert mask.sum() > 30
    diff = np.abs(bad.s0 - good.s0)
    near = cv2.dilate(mask.astype(np.uint8), np.ones((7, 7), np.uint8)).astype(bool)
    scale = float(good.s0.max())
    assert diff[mask].max() > 1e-2 * scale
    assert np.mean(diff[~near] > 1e-3 * scale) < 0.005
    assert np.array_equal(bad.object_mask[~near], good.object_mask[~near])


def test_a_render_window_shows_the_full_images_pixels(scene_case) -> None:
    model, params, _ = scene_case
    full = render_sample(model, params, None, RenderSettings(**SMALL, spp=1), 2)
    ys, xs = np.nonzero(full.object_mask)
    for x0, y0 in ((int(xs.min()) - 6, int(ys.min()) - 6), (int(xs.max()) - 26, int(ys.max()) - 26)):
        x0, y0 = min(max(0, x0 - x0 % 2), 128 - 32), min(max(0, y0 - y0 % 2), 96 - 32)
        win = render_sample(model, params, None, RenderSettings(**SMALL, spp=1, window=(x0, y0, 32, 32)), 2)
        assert win.object_mask.shape == (32, 32)
        assert np.mean(win.object_mask == full.object_mask[y0:y0 + 32, x0:x0 + 32]) > 0.97


def test_defect_window_holds_the_mask_with_even_offsets() -> None:
    mask = np.zeros((480, 640), bool)
    mask[101:140, 3:60] = True
    x0, y0, w, h = defect_window(mask)
    assert (w, h) == (128, 64) and x0 % 2 == 0 and y0 % 2 == 0 and x0 == 0
    assert mask[y0:y0 + h, x0:x0 + w].sum() == mask.sum()
