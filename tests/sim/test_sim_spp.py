"""spp from a target DoLP error (the measured curve), renderer-version checks on resume, and unbiased light
sampling weights."""

from __future__ import annotations

import json

import numpy as np
import pytest

from sim.errors import SimError
from sim.render import RENDERER_VERSION
from sim.spp import SPP_TABLE, load_table, spp_for_dolp_error

CURVE = [{"spp": 1, "dolp_rmse": 0.2}, {"spp": 4, "dolp_rmse": 0.1}, {"spp": 16, "dolp_rmse": 0.05},
         {"spp": 64, "dolp_rmse": 0.025}]


def _table(tmp_path, points=CURVE, version=RENDERER_VERSION):
    path = tmp_path / "spp.json"
    path.write_text(json.dumps({"renderer_version": version, "width": 640, "height": 480, "measured": "test",
                                "points": points}))
    return path


def test_smallest_spp_meeting_the_target_on_the_log_log_curve(tmp_path) -> None:
    path = _table(tmp_path)
    assert spp_for_dolp_error(0.1, path=path).spp == 4  # a measured point is met exactly
    assert spp_for_dolp_error(0.3, path=path).spp == 1
    # error ~ spp^-1/2 between 4 and 16: 0.07 needs 4 * (0.1/0.07)^2 = 8.2 -> 9
    choice = spp_for_dolp_error(0.07, path=path)
    assert choice.spp == 9 and choice.predicted_dolp_error <= 0.07
    assert 16 < spp_for_dolp_error(0.0251, path=path).spp <= 64
    with pytest.raises(SimError, match="below the smallest DoLP error measured"):
        spp_for_dolp_error(0.02, path=path)
    with pytest.raises(SimError, match="in \\(0, 1\\)"):
        spp_for_dolp_error(0.0, path=path)


def test_sampler_spp_is_what_mitsuba_renders() -> None:
    import mitsuba as mi

    from sim.scene import SAMPLER, sampler_spp
    from sim.variant import set_variant

    set_variant()
    level = mi.log_level()
    mi.set_log_level(mi.LogLevel.Error)  # rounding warnings
    try:
        taken = [mi.load_dict({"type": SAMPLER, "sample_count": n}).sample_count() for n in range(1, 70)]
    finally:
        mi.set_log_level(level)
    assert [sampler_spp(n) for n in range(1, 70)] == taken
    assert sampler_spp(32) == 35 and sampler_spp(16) == 16


def test_a_curve_of_another_renderer_or_a_broken_one_is_refused(tmp_path) -> None:
    with pytest.raises(SimError, match="renderer version 1"):
        spp_for_dolp_error(0.05, path=_table(tmp_path, version=1))
    with pytest.raises(SimError, match="need >= 2 points"):
        load_table(_table(tmp_path, points=CURVE[:1]))
    bad = tmp_path / "bad.json"
    bad.write_text("{")
    with pytest.raises(SimError, match=r"bad\.json"):
        load_table(bad)


def test_the_shipped_curve_is_for_this_renderer() -> None:
    table = load_table(SPP_TABLE)
    errs = [p["dolp_rmse"] for p in sorted(table["points"], key=lambda p: p["spp"])]
    assert errs[0] > errs[-1] > 0


def test_render_dolp_error_chooses_spp_and_resume_refuses_another_renderer(tmp_path, capsys) -> None:
    from station.cli import main

    out = tmp_path / "ds"
    argv = ["render", "--out", str(out), "--count", "1", "--width", "64", "--height", "48", "--defects", "0"]
    target = max(p["dolp_rmse"] for p in load_table(SPP_TABLE)["points"])  # the cheapest point of the curve
    assert main([*argv, "--dolp-error", str(target)]) == 0
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["renderer_version"] == RENDERER_VERSION
    assert manifest["spp_choice"]["dolp_error_target"] == target
    assert manifest["config"]["spp"] == manifest["spp_choice"]["spp"] == spp_for_dolp_error(target).spp
    capsys.readouterr()
    with pytest.raises(SystemExit):  # one or the other
        main([*argv, "--dolp-error", "0.1", "--spp", "4"])
    capsys.readouterr()
    # a set from the previous renderer (no renderer_version key = version 1) is not resumed with this one
    manifest.pop("renderer_version")
    (out / "manifest.json").write_text(json.dumps(manifest))
    assert main([*argv, "--spp", str(manifest["config"]["spp"])]) == 2
    err = capsys.readouterr().err
    assert "renderer version 1" in err and f"version {RENDERER_VERSION}" in err


def test_light_sampling_weights_change_noise_not_the_image() -> None:
    """Same scene, uniform vs irradiance-proportional emitter choice: the mean radiance of the image agrees
    (the estimator stays unbiased); a weight applied as a brightness factor would move it by >> 5 %."""
    import mitsuba as mi

    from sim.meshes import usb_brick
    from sim.render import _channels, _integrator, load_scene
    from sim.scene import SceneConfig, build_scene, emitter_weights, object_to_world, pose_parts, sample_scene
    from sim.variant import set_variant

    set_variant()
    model = usb_brick()
    params = sample_scene(np.random.default_rng([0, 5]), SceneConfig(ambient_radiance=0.2), model)
    spot_w, ambient_w = emitter_weights(params)
    assert spot_w > 3 * ambient_w > 0
    parts = pose_parts(model, object_to_world(params["pose"]))
    means = []
    for uniform in (False, True):
        d, _ = build_scene(params, parts, params["materials"], 32, 24, 64)
        if uniform:
            d["spot"]["sampling_weight"] = d["ambient"]["sampling_weight"] = 1.0
        scene = load_scene(d)
        mi.render(scene, integrator=_integrator("stokes"), spp=64, seed=3)
        means.append(float(_channels(scene)["S0"][..., 0].mean()))
    assert means[0] == pytest.approx(means[1], rel=0.05)


@pytest.mark.parametrize(("ring", "sector"), [(0.0, (0.0, 360.0)), (5.89, (0.0, 360.0)), (2.6, (70.0, 110.0))])
def test_every_environment_gets_its_sampling_weight(ring: float, sector: tuple[float, float]) -> None:
    """The ring light's environment was built without its weight (Mitsuba's default, 1, against the stray spot's
    I / d^2 of up to 0.6): the spot took up to 37 % of the emitter samples instead of up to 21 %, and the ring's renders
    were noisier than they need be (unbiased either way). A sector's weight counts only its share of the ring, and
    the sector reaches the scene."""
    from sim.meshes import usb_brick
    from sim.scene import (
        SceneConfig,
        build_scene,
        emitter_weights,
        object_to_world,
        pose_parts,
        ring_irradiance_factor,
        sample_scene,
    )
    from sim.variant import set_variant

    set_variant()
    model = usb_brick()
    cfg = SceneConfig(ambient_radiance=0.35, ring_radiance=ring, ring_azimuth_deg=sector, light_intensity=(0.5, 0.5))
    params = sample_scene(np.random.default_rng([0, 5]), cfg, model)
    d, _ = build_scene(params, pose_parts(model, object_to_world(params["pose"])), params["materials"], 32, 24, 4)
    assert (d["spot"]["sampling_weight"], d["ambient"]["sampling_weight"]) == emitter_weights(params)
    ring_share = (emitter_weights(params)[1] - 0.35 * np.pi) / (ring * ring_irradiance_factor(5, 15) or 1)
    assert ring_share == pytest.approx((sector[1] - sector[0]) / 360 if ring else 0.0)
    if ring:
        columns = np.array(d["ambient"]["bitmap"]).shape[1]
        assert columns == (4 if sector == (0.0, 360.0) else 1440)
