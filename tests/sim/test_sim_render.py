"""Tiny Mitsuba renders: shape-index mapping, AoLP/normal conventions, defect masks, dataset determinism,
resume and atomic writes, and errors raised before rendering."""

from __future__ import annotations

import copy
import json

import numpy as np
import pytest

from model.priors.stokes import aolp, dolp
from sim.dataset import Dataset, DatasetSpec, generate_sample, init_dataset, prepare, write_sample
from sim.defects import DefectConfig, apply_defect
from sim.errors import SimError
from sim.meshes import usb_brick
from sim.render import RenderSettings, load_scene, render_sample, shape_ids
from sim.scene import SceneConfig, object_to_world, sample_scene, sensor_dict
from sim.variant import set_variant

TINY = {"width": 64, "height": 48, "spp": 4}


@pytest.fixture(scope="module")
def variant() -> str:
    return set_variant()


def _channels(scene) -> dict[str, np.ndarray]:
    film = scene.sensors()[0].film()
    return {n: np.array(b) for n, b in film.bitmap().split()}


def test_shape_index_maps_to_the_right_shape(variant: str) -> None:
    import mitsuba as mi

    cam = {"origin": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0], "fov_x_deg": 60}
    scene = load_scene({"type": "scene", "sensor": sensor_dict(cam, 32, 24, 1),
                        "left": {"type": "sphere", "center": [-0.6, 0, 0], "radius": 0.4},
                        "right": {"type": "sphere", "center": [0.6, 0, 0], "radius": 0.4}})
    mi.render(scene, integrator=mi.load_dict({"type": "aov", "aovs": "sid:shape_index"}), spp=1)
    sid = np.rint(_channels(scene)["sid"]).astype(int)
    ids = shape_ids(scene)
    # image right is world +x here (camera looks down -z with y up)
    assert sid[12, 16 + 5] == ids["right"] and sid[12, 16 - 5] == ids["left"] and sid[12, 16] == 0


def test_specular_sphere_aolp_is_tangential_and_normals_in_camera_frame(variant: str) -> None:
    """Specular reflection polarizes perpendicular to the plane of incidence: AoLP = normal azimuth + 90 deg,
    with AoLP counted from image right toward image up and normals x right, y up (conventions.py)."""
    import mitsuba as mi

    from sim.render import _channels as render_channels
    from sim.render import _integrator
    from sim.scene import camera_axes

    cam = {"origin": [0.3, -0.2, 3], "target": [0, 0, 0], "up": [0, 1, 0], "fov_x_deg": 30}
    scene = load_scene({"type": "scene", "sensor": sensor_dict(cam, 64, 48, 16),
                        "ball": {"type": "sphere", "radius": 0.5,
                                 "bsdf": {"type": "pplastic", "diffuse_reflectance": {"type": "rgb", "value": 0.0},
                                          "alpha": 0.01}},
                        "env": {"type": "constant"}})
    mi.render(scene, integrator=_integrator("stokes"), spp=16)
    ch = render_channels(scene)
    s0, s1, s2 = (ch[k][..., 0] for k in ("S0", "S1", "S2"))
    mi.render(scene, integrator=_integrator("aov"), spp=1)
    ch = render_channels(scene)
    n = ch["nn"].reshape(48, 64, 3) @ camera_axes(cam).T
    sel = (np.rint(ch["sid"]) > 0) & (dolp(s0, s1, s2) > 0.2) & (np.hypot(n[..., 0], n[..., 1]) > 0.3)
    assert sel.sum() > 50
    assert np.all(n[..., 2][sel] > 0)  # the visible half faces the camera (+z toward the camera)
    # the rim on image right has normal (+x); row 0 is the top, so image up is -row
    row, col = np.nonzero(sel)
    centre_r, centre_c = np.mean(np.nonzero(np.rint(ch["sid"]) > 0), axis=1)
    azimuth_img = np.arctan2(-(row - centre_r), col - centre_c)
    azimuth_n = np.arctan2(n[..., 1][sel], n[..., 0][sel])
    assert np.median(np.abs(np.angle(np.exp(1j * (azimuth_img - azimuth_n))))) < np.radians(10)
    expected = azimuth_n + np.pi / 2
    err = np.angle(np.exp(2j * (aolp(s1, s2)[sel] - expected))) / 2
    assert np.degrees(np.median(np.abs(err))) < 5


@pytest.mark.parametrize(("gradient", "azimuth"), [(0.0, 0.0), (0.8, 0.0), (0.8, 180.0)])
def test_gradient_dome_lights_the_plus_x_side(variant: str, gradient: float, azimuth: float) -> None:
    """``SceneConfig.ambient_gradient``: a matte sphere under the dome has S0 = c (1 + 2/3 g n_x) (irradiance of
    the radiance L (1 + g w_x) over a normal's hemisphere), its +x side (image right) the brighter; with
    ``ambient_gradient_azimuth_deg`` 180 the -x side, c (1 - 2/3 g n_x)."""
    import mitsuba as mi

    from sim.render import _channels as render_channels
    from sim.render import _integrator
    from sim.scene import ambient_dict, camera_axes

    cam = {"origin": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0], "fov_x_deg": 30}
    scene = load_scene({"type": "scene", "sensor": sensor_dict(cam, 64, 64, 64),
                        "ball": {"type": "sphere", "radius": 0.7, "bsdf": {"type": "diffuse"}},
                        "env": ambient_dict(0.7, gradient, azimuth)})
    mi.render(scene, integrator=_integrator("stokes"), spp=64)
    s0 = render_channels(scene)["S0"][..., 0]
    mi.render(scene, integrator=_integrator("aov"), spp=1)
    ch = render_channels(scene)
    nx = (ch["nn"].reshape(64, 64, 3) @ camera_axes(cam).T)[..., 0]  # camera x is world x here
    on = (np.rint(ch["sid"]) > 0) & (np.abs(nx) < 0.8)
    slope, c = np.polyfit(nx[on], s0[on], 1)
    assert slope / c == pytest.approx(2 / 3 * gradient * np.cos(np.radians(azimuth)), abs=0.05)
    assert c == pytest.approx(0.7 / 2, rel=0.05)  # albedo 0.5 under a mean radiance of 0.7: the mean is kept


def _ring_irradiance(n: np.ndarray, lo_deg: float, hi_deg: float, radiance: float,
                     azimuth_deg: tuple[float, float] = (0.0, 360.0)) -> np.ndarray:
    """Irradiance on faces of normals ``n`` (..., 3) from a ring of ``radiance`` at elevations [lo, hi] and
    azimuths ``azimuth_deg`` (from world +x toward +y), by a sum over the ring's directions (the reference
    ``ring_dict`` must match)."""
    de = np.radians(hi_deg - lo_deg) / 60
    da = np.radians(azimuth_deg[1] - azimuth_deg[0]) / 180
    e = np.radians(lo_deg) + (np.arange(60) + 0.5) * de  # cell midpoints
    a = np.radians(azimuth_deg[0]) + (np.arange(180) + 0.5) * da
    ee, aa = np.meshgrid(e, a, indexing="ij")
    w = np.stack([np.cos(ee) * np.cos(aa), np.cos(ee) * np.sin(aa), np.sin(ee)], -1).reshape(-1, 3)
    d_omega = np.cos(ee).ravel() * de * da
    return radiance * (np.clip(n @ w.T, 0, None) * d_omega).sum(-1)


def _matte_sphere_under(env: dict) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """S0 of a matte sphere (albedo 0.5) seen from world +z with image up along world +y, so camera axes are world
    axes; its world normals, and the pixels on the sphere off its rim (whose pixels are part background)."""
    import mitsuba as mi

    from sim.render import _channels as render_channels
    from sim.render import _integrator
    from sim.scene import camera_axes

    cam = {"origin": [0, 0, 3], "target": [0, 0, 0], "up": [0, 1, 0], "fov_x_deg": 30}
    scene = load_scene({"type": "scene", "sensor": sensor_dict(cam, 64, 64, 64),
                        "ball": {"type": "sphere", "radius": 0.7, "bsdf": {"type": "diffuse"}}, "env": env})
    mi.render(scene, integrator=_integrator("stokes"), spp=64)
    s0 = render_channels(scene)["S0"][..., 0]
    mi.render(scene, integrator=_integrator("aov"), spp=1)
    ch = render_channels(scene)
    n = ch["nn"].reshape(64, 64, 3) @ camera_axes(cam).T  # camera axes are world axes here
    return s0, n, (np.rint(ch["sid"]) > 0) & (n[..., 2] > 0.45)


def test_ring_light_lights_a_face_as_its_irradiance_says(variant: str) -> None:
    """``SceneConfig.ring_radiance``: a matte sphere under a ring at elevations 5-15 degrees (no dome) has S0 =
    albedo / pi * E(n), E the ring's irradiance on its normal: dark on top (``ring_irradiance_factor``), bright on
    faces tilted toward the horizon."""
    from sim.scene import ring_dict, ring_irradiance_factor

    s0, n, on = _matte_sphere_under(ring_dict(0.0, 10.0, (5.0, 15.0)))
    expected = 0.5 / np.pi * _ring_irradiance(n[on], 5.0, 15.0, 10.0)
    assert np.corrcoef(expected, s0[on])[0, 1] > 0.9
    assert np.median(s0[on] / np.maximum(expected, 1e-3)) == pytest.approx(1.0, rel=0.05)
    top = on & (n[..., 2] > 0.99)
    assert np.mean(s0[top]) == pytest.approx(0.5 / np.pi * 10.0 * ring_irradiance_factor(5.0, 15.0), rel=0.1)
    assert _ring_irradiance(np.array([0.0, 0, 1]), 5, 15, 1.0) == pytest.approx(ring_irradiance_factor(5, 15), rel=0.01)


def test_a_ring_sector_lights_the_faces_on_its_side(variant: str) -> None:
    """``SceneConfig.ring_azimuth_deg``: a sector of the ring at azimuths 30-90 (between world +x and +y, not
    symmetric about either) lights a matte sphere as its irradiance says, so its columns sit at the right
    azimuths (a mirrored or shifted map lights other faces); on top, the whole ring's irradiance times 60/360."""
    from sim.scene import ring_dict, ring_irradiance_factor

    sector = (30.0, 90.0)
    s0, n, on = _matte_sphere_under(ring_dict(0.0, 10.0, (20.0, 45.0), sector))
    expected = 0.5 / np.pi * _ring_irradiance(n[on], 20.0, 45.0, 10.0, sector)
    assert np.corrcoef(expected, s0[on])[0, 1] > 0.95
    lit = expected > 0.2 * expected.max()
    assert np.median(s0[on][lit] / expected[lit]) == pytest.approx(1.0, rel=0.05)
    mirrored = 0.5 / np.pi * _ring_irradiance(n[on] * [1, -1, 1], 20.0, 45.0, 10.0, sector)
    assert np.corrcoef(mirrored, s0[on])[0, 1] < 0.5
    top = on & (n[..., 2] > 0.99)
    assert np.mean(s0[top]) == pytest.approx(0.5 / np.pi * 10.0 * ring_irradiance_factor(20, 45, *sector), rel=0.1)
    assert ring_irradiance_factor(20, 45, *sector) == pytest.approx(ring_irradiance_factor(20, 45) / 6)


def test_ring_fringes_modulate_the_panel_across_elevation(variant: str) -> None:
    """``SceneConfig.ring_fringe_period_deg``: the ring's rows (polar angles from the vertical, a quarter of a degree
    each) carry 1 + depth cos(2 pi (e - e_lo) / period + phase) at their elevation e, outside the ring nothing
    changes, and three whole periods keep the ring's mean radiance."""
    from sim.scene import RING_ROWS, ring_dict

    plain = np.array(ring_dict(0.7, 10.0, (22.0, 46.0), (70.0, 110.0))["bitmap"]).reshape(RING_ROWS, -1)
    striped = np.array(ring_dict(0.7, 10.0, (22.0, 46.0), (70.0, 110.0), (8.0, 0.5))["bitmap"]).reshape(RING_ROWS, -1)
    elevation = 90.0 - (np.arange(RING_ROWS) + 0.5) * 180.0 / RING_ROWS
    inside = (elevation > 22.2) & (elevation < 45.8)
    expected = 0.7 + 10.0 * (1 + 0.5 * np.cos(2 * np.pi * (elevation[inside] - 22.0) / 8.0))
    np.testing.assert_allclose(striped[inside].max(1), expected, rtol=1e-5)
    outside = (elevation < 21.8) | (elevation > 46.2)
    np.testing.assert_array_equal(striped[outside], plain[outside])
    assert striped.sum() == pytest.approx(plain.sum(), rel=1e-3)
    uniform = ring_dict(0.7, 10.0, (22.0, 46.0), (70.0, 110.0), (0.0, 0.5))["bitmap"]  # period 0: no fringes
    np.testing.assert_array_equal(np.array(uniform).reshape(RING_ROWS, -1), plain)
    shifted = np.array(ring_dict(0.7, 10.0, (22.0, 46.0), (70.0, 110.0), (8.0, 0.5, 90.0))["bitmap"])
    expected = 0.7 + 10.0 * (1 + 0.5 * np.cos(2 * np.pi * (elevation[inside] - 22.0) / 8.0 + np.pi / 2))
    np.testing.assert_allclose(shifted.reshape(RING_ROWS, -1)[inside].max(1), expected, rtol=1e-5)
    with pytest.raises(SimError, match="ring_fringe_period_deg"):
        SceneConfig(ring_fringe_period_deg=8.0)
    with pytest.raises(SimError, match="ring_fringe_depth"):
        SceneConfig(ring_radiance=2.6, ring_fringe_period_deg=8.0, ring_fringe_depth=1.5)


@pytest.mark.parametrize("azimuth", [0.0, 180.0])
def test_a_ring_sector_over_a_gradient_dome_lights_a_face_as_the_sum_of_their_irradiances(variant: str,
                                                                                          azimuth: float) -> None:
    """``ring_dict`` with ``gradient``: a bright-field panel (a ring sector) over one lit half of a segmented dome
    lights a matte sphere as the panel's irradiance plus the gradient dome's, pi L (1 + 2/3 g n_a) (n_a: the normal
    along the lit side's azimuth); the dome lit from the other side does not match. The two halves' maps average to
    the plain ring's over a uniform dome (a segmented dome's frames' mean is the whole dome's frame)."""
    from sim.scene import RING_ROWS, ring_dict

    sector, g = (30.0, 90.0), 0.8
    s0, n, on = _matte_sphere_under(ring_dict(0.7, 10.0, (20.0, 45.0), sector, gradient=g,
                                              gradient_azimuth_deg=azimuth))
    ring = 0.5 / np.pi * _ring_irradiance(n[on], 20.0, 45.0, 10.0, sector)

    def dome(az: float) -> np.ndarray:
        n_a = n[on][:, 0] * np.cos(np.radians(az)) + n[on][:, 1] * np.sin(np.radians(az))
        return 0.5 * 0.7 * (1 + 2 / 3 * g * n_a)

    assert np.median(np.abs(s0[on] / (ring + dome(azimuth)) - 1)) < 0.05
    assert np.median(np.abs(s0[on] / (ring + dome(azimuth + 180)) - 1)) > 0.15

    def bitmap(**gradient: float) -> np.ndarray:
        return np.array(ring_dict(0.7, 10.0, (20.0, 45.0), sector, **gradient)["bitmap"]).reshape(RING_ROWS, -1)

    halves = [bitmap(gradient=g, gradient_azimuth_deg=a) for a in (azimuth, (azimuth + 180) % 360)]
    np.testing.assert_allclose((halves[0] + halves[1]) / 2, bitmap(), rtol=1e-5, atol=1e-6)
    SceneConfig(ring_radiance=5.0, ambient_gradient=0.8)  # one environment holds both


def test_ring_elevations_are_checked() -> None:
    with pytest.raises(SimError, match="ring_elevation_deg"):
        SceneConfig(ring_radiance=5.0, ring_elevation_deg=(15.0, 95.0))
    with pytest.raises(SimError, match="ring_azimuth_deg"):
        SceneConfig(ring_radiance=5.0, ring_azimuth_deg=(90.0, 70.0))


@pytest.mark.parametrize(("azimuth", "x", "y"), [(270.0, (-0.025, 0.025), (-0.040, -0.011)),
                                                   (0.0, (0.011, 0.040), (-0.025, 0.025))])
def test_the_front_light_lies_where_its_config_says(variant: str, azimuth: float, x: tuple, y: tuple) -> None:
    """``SceneConfig.front_light_*``: a strip on the belt from 11 to 40 mm toward ``front_light_azimuth_deg``, 50 mm
    across, just above the ground, emitting upward."""
    import mitsuba as mi

    from sim.scene import FRONT_LIGHT_HEIGHT_M, front_light_dict

    light = {"radiance": 2.0, "span_m": [0.011, 0.040], "width_m": 0.05, "azimuth_deg": azimuth}
    strip = mi.load_dict(front_light_dict(light))
    box = strip.bbox()
    np.testing.assert_allclose([box.min[0], box.max[0], box.min[1], box.max[1]], [*x, *y], atol=1e-6)
    assert box.min[2] == pytest.approx(FRONT_LIGHT_HEIGHT_M, abs=1e-6)
    assert strip.is_emitter()
    si = strip.eval_parameterization([0.5, 0.5])  # the strip's centre: its normal points up
    assert float(si.n.z[0]) == pytest.approx(1.0)


def test_the_front_light_puts_the_front_face_in_bright_field(variant: str) -> None:
    """The line's camera (56 degrees off vertical, from -y) sees the brick's front face (facing -y) mirror the belt
    in front of it: with the strip there, that face reads brighter and polarized (specular light at 34 degrees
    incidence is about half polarized), and the top face, which the strip cannot light, stays as it was."""
    model = usb_brick()
    line = {"camera_radius_m": (0.39, 0.39), "camera_polar_deg": (56.0, 56.0), "camera_azimuth_deg": (270.0, 270.0),
            "camera_target_jitter_m": 0.0, "focal_length_mm": 120.0, "object_xy_m": 0.0, "yaw_deg": (0.0, 0.0),
            "rest_pose": 0, "light_intensity": (0.0, 0.0), "ambient_radiance": 0.7, "colour": (0.55, 0.55),
            "background_colour": (0.1, 0.1), "backgrounds": ("plain",)}
    faces = {}
    for radiance in (0.0, 2.1):
        params = sample_scene(np.random.default_rng(2), SceneConfig(front_light_radiance=radiance, **line), model)
        out = render_sample(model, params, None, RenderSettings(width=96, height=72, spp=36), seed=1)
        body = out.object_mask & (out.part_index == 1)
        front, top = body & (out.normal[..., 2] > 0.78), body & (out.normal[..., 2] < 0.65)
        d = dolp(out.s0, out.s1, out.s2)
        faces[radiance] = (np.median(out.s0[front]), np.median(d[front]), np.median(out.s0[top]))
    (f0, p0, t0), (f1, p1, t1) = faces[0.0], faces[2.1]
    assert f1 > 2 * f0 and p1 > 0.03 > p0
    assert t1 == pytest.approx(t0, rel=0.1)


def test_the_front_light_refuses_an_empty_strip() -> None:
    with pytest.raises(SimError, match="front_light_span_m"):
        SceneConfig(front_light_radiance=2.0, front_light_span_m=(0.04, 0.011))
    with pytest.raises(SimError, match="front_light_azimuth_deg"):
        SceneConfig(front_light_azimuth_deg=360.0)


@pytest.fixture(scope="module")
def brick_case(variant: str):
    model = usb_brick()
    cfg = SceneConfig(focal_length_mm=150.0, camera_target_jitter_m=0.0, camera_polar_deg=(20.0, 40.0))
    params = sample_scene(np.random.default_rng(5), cfg, model)
    return model, params


def _defect(model, params, kind: str):
    to_world = object_to_world(params["pose"])
    cam_obj = np.linalg.solve(to_world, np.r_[params["camera"]["origin"], 1.0])[:3]
    cfg = DefectConfig(types=(kind,), stain_radius_mm=(3.0, 3.5), dent_radius_mm=(2.5, 3.0), dent_depth_mm=(0.4, 0.5),
                       blister_radius_mm=(2.5, 3.0), blister_height_mm=(0.4, 0.5), debris_radius_mm=(1.0, 1.2))
    return apply_defect(model, kind, np.random.default_rng(1), cfg, cam_obj, params["materials"])


@pytest.mark.parametrize("kind", ["stain", "dent", "missing_stud", "blister", "debris"])
def test_defect_mask_visible_then_hidden(brick_case, kind: str) -> None:
    model, params = brick_case
    defect = _defect(model, params, kind)
    settings = RenderSettings(**TINY)
    seen = render_sample(model, params, defect, settings, seed=1)
    assert seen.defect_mask.sum() > 0
    assert np.all(seen.object_mask[seen.defect_mask] | (kind == "missing_stud"))
    # camera on the opposite side, same height: the defect faces away (hidden by the object itself)
    other = copy.deepcopy(params)
    o, t = np.array(params["camera"]["origin"]), np.array(params["camera"]["target"])
    other["camera"]["origin"] = [2 * t[0] - o[0], 2 * t[1] - o[1], o[2]]
    behind = render_sample(model, other, defect, settings, seed=1)
    assert behind.object_mask.sum() > 0 and behind.defect_mask.sum() == 0
    # camera turned away from the object: out of view
    away = copy.deepcopy(params)
    away["camera"]["target"] = (2 * o - t).tolist()
    assert render_sample(model, away, defect, settings, seed=1).defect_mask.sum() == 0


def test_no_ground_truth_skips_the_aov_pass(brick_case) -> None:
    model, params = brick_case
    out = render_sample(model, params, None, RenderSettings(**TINY, ground_truth=False), seed=1)
    assert out.normal is None and out.defect_mask is None and "gt_s" not in out.seconds
    assert out.s0.shape == (48, 64) and out.s0.max() > 0


def _spec(**kw) -> DatasetSpec:
    return DatasetSpec(seed=3, defect_fraction=1.0, **TINY, **kw)


def test_dataset_deterministic_resumable_atomic(tmp_path, monkeypatch) -> None:
    from station.cli import main

    out = tmp_path / "ds"
    argv = ["render", "--out", str(out), "--count", "3", "--width", "64", "--height", "48", "--spp", "4",
            "--seed", "3", "--defects", "1.0"]
    assert main(argv) == 0
    ds = Dataset(out)
    assert len(ds) == 3 and ds.indices("test") == [0, 1] and ds.indices("val") == [2]
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["format"] == "polar-ano-dataset" and manifest["count"] == 3
    s = ds.load(2)
    assert s.raw.dtype == np.uint8 and s.raw.shape == (48, 64)
    assert s.normal.shape == (48, 64, 3) and s.s0.dtype == np.float32
    assert s.label == int(s.defect_mask.any()) and s.params["defect"] is not None
    first = ds.load(1).raw
    # resume: nothing left to do; a removed sample is re-rendered alone, identically
    import shutil

    shutil.rmtree(out / "samples" / "000001")
    assert main(argv) == 0
    np.testing.assert_array_equal(Dataset(out).load(1).raw, first)
    # a crash while writing leaves no sample that looks complete, and the leftover is cleaned on resume
    spec = _spec()
    model = prepare(spec)
    sample = generate_sample(spec, model, 4)

    def boom(*a, **k):
        raise OSError("disk full")

    monkeypatch.setattr("sim.dataset.save_npz", boom)
    with pytest.raises(OSError):
        write_sample(out, sample)
    assert 4 not in Dataset(out).indices() and list((out / "samples").glob("000004.tmp-*"))
    monkeypatch.undo()
    init_dataset(out, spec, 5)
    assert not list((out / "samples").glob("*.tmp-*"))


def test_bad_input_fails_before_rendering(tmp_path, capsys) -> None:
    from station.cli import main

    base = ["render", "--out", str(tmp_path / "x"), "--count", "1"]
    assert main([*base, "--mesh", str(tmp_path / "missing.ply")]) == 2
    assert "missing.ply" in capsys.readouterr().err
    import trimesh

    ply = tmp_path / "cube.ply"
    trimesh.creation.box([0.02, 0.02, 0.02]).export(ply)
    assert main([*base, "--mesh", str(ply), "--materials", '{"*": "pplasticx"}']) == 2
    assert "pplasticx" in capsys.readouterr().err
    cfg = tmp_path / "c.json"
    cfg.write_text(json.dumps({"scene": {"camera_radius_m": [0.5, 0.4]}}))
    assert main([*base, "--config", str(cfg)]) == 2
    assert "camera_radius_m" in capsys.readouterr().err
    assert not (tmp_path / "x" / "samples").exists()


def test_user_mesh_with_material_map_renders(tmp_path, variant: str) -> None:
    import trimesh

    ply = tmp_path / "cube.ply"
    trimesh.creation.box([0.03, 0.03, 0.02]).export(ply)
    spec = DatasetSpec(seed=1, defect_fraction=1.0, mesh=str(ply), materials={"*": {"type": "roughconductor",
                                                                                  "material": "Cu"}}, **TINY)
    model = prepare(spec)
    sample = generate_sample(spec, model, 0)
    assert sample.object_mask.sum() > 20
    assert sample.params["scene"]["materials"]["cube"]["type"] == "roughconductor"


@pytest.mark.parametrize("roi", ["center", "band"])
def test_a_frame_of_the_whole_sensor_shows_the_model_the_part_at_its_trained_size(variant: str, roi: str) -> None:
    """The renders are 4:3 crops of the sensor's width (the field of view runs along x); the whole IMX250MZR sensor
    is 2448 x 2048, taller. The same scene at the sensor's shape must fill the region of a model trained on 4:3
    frames as the 4:3 frame does (the frame's own min(height, width) square made the part 0.9 times as large)."""
    import cv2

    from model.draem.roi import roi_box

    model = usb_brick()  # the shipped line's geometry (sim/presets/line-polar.toml), the part well inside the view
    cfg = SceneConfig(camera_target_jitter_m=0.0, camera_radius_m=(0.38, 0.40), camera_polar_deg=(54.0, 58.0),
                      yaw_deg=(-5.0, 5.0), rest_pose=0)
    params = sample_scene(np.random.default_rng(5), cfg, model)
    masks = {}
    for h in (96, 108):  # 128 x 96 (4:3, as trained) and 128 x 108 (the sensor's 1.19)
        mask = render_sample(model, params, None, RenderSettings(width=128, height=h, spp=1), seed=1).object_mask
        top, left, bh, bw = roi_box(roi, mask.shape, frame_aspect=128 / 96)
        masks[h] = cv2.resize(mask[top:top + bh, left:left + bw].astype(np.float32), (64, 64 * bh // bw),
                              interpolation=cv2.INTER_AREA)
    assert 50 < masks[96].sum() < 0.9 * masks[96].size
    assert masks[108].sum() / masks[96].sum() == pytest.approx(1.0, abs=0.04)
    assert np.abs(masks[108] - masks[96]).mean() < 0.03


def test_a_dome_segment_set_images_each_part_once_per_segment_with_its_own_noise(tmp_path, capsys) -> None:
    """``--dome-segments 0,180``: the first frame is the one-frame set rendered under segment 0 (the same draws),
    the second the same part lit from -x with independent noise; the manifest and ``Dataset`` say how many frames
    a part has. Without a gradient dome the option is refused in one line."""
    from station.cli import main

    dome = tmp_path / "dome.toml"
    dome.write_text("[scene]\nambient_gradient = 0.8\n")
    base = ["render", "--count", "2", "--width", "64", "--height", "48", "--spp", "4", "--seed", "7",
            "--defects", "0", "--config", str(dome)]
    assert main([*base, "--dome-segments", "0,180", "--out", str(tmp_path / "pair")]) == 0
    assert main([*base, "--out", str(tmp_path / "one")]) == 0
    pair, one = Dataset(tmp_path / "pair"), Dataset(tmp_path / "one")
    assert pair.dome_segments == (0.0, 180.0) and one.dome_segments == ()
    assert json.loads((tmp_path / "pair" / "manifest.json").read_text())["config"]["dome_segments"] == [0.0, 180.0]
    assert "dome_segments" not in json.loads((tmp_path / "one" / "manifest.json").read_text())["config"]
    for i in range(2):
        s, s1 = pair.load(i), one.load(i)
        assert len(s.raws) == 2 and len(s1.raws) == 1
        np.testing.assert_array_equal(s.raws[0], s1.raw)
        assert s.params["dome_segments"][1]["azimuth_deg"] == 180.0
        assert s.params["dome_segments"][1]["mitsuba_seed"] != s.params["mitsuba_seed"]
        obj = s.object_mask
        a, b = (r.astype(np.float64) for r in s.raws)
        assert np.abs(a - b)[obj].mean() > 1.0  # lit from the other side: another frame
        # the ground-truth Stokes are the uniform dome's: the mean of the two lit halves
        assert s.s0.shape == (48, 64) and np.isfinite(s.s0).all()
    capsys.readouterr()
    assert main([*base[:-2], "--dome-segments", "0,180", "--out", str(tmp_path / "flat")]) == 2
    err = capsys.readouterr().err
    assert "ambient_gradient" in err and len(err.strip().splitlines()) == 1


def test_the_scalar_fallback_renders_a_part(tmp_path) -> None:
    """Without LLVM >= 19 the renderer falls back to ``scalar_spectral_polarized`` (``sim.variant``). Its mesh
    buffers are dynamic scalar arrays, not ``mi.Float``: a tiny sample, the striped flat dome included, renders finite
    Stokes there. In a subprocess: a process keeps the variant it first set."""
    import os
    import subprocess
    import sys

    code = """
import numpy as np
from sim import dataset as sd
from sim.render import render_sample
import mitsuba as mi
spec = sd.DatasetSpec(seed=5, defect_fraction=0.0, width=32, height=24, spp=1,
                      view={"camera_height_m": [0.002, 0.002], "flat_dome_radiance": 5.0,
                            "flat_dome_fringe_period_m": 0.12})
model = sd.prepare(spec)
draw = sd.draw_sample(spec, model, 0)
out = render_sample(model, draw.params, None, spec.render_settings(), draw.mitsuba_seed)
assert np.isfinite(out.s0).all() and out.s0.max() > 0 and out.object_mask.any()
print(mi.variant())
"""
    env = {**os.environ, "POLAR_ANO_MI_VARIANT": "scalar_spectral_polarized", "PYTHONPATH": os.getcwd()}
    run = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.strip().endswith("scalar_spectral_polarized")


def test_the_scalar_fallback_renders_the_mono_camera_s_brightness() -> None:
    """The spectral fallback's film holds R, G and B; a mono polarization camera sees their luminance, as the mono
    variants render it. Reading the red channel made a part of colour (0.97, 0.90, 0.84) on a ground of another
    colour 1.55 times as bright as the mono render of the same sample. The same sample in both variants: the
    frame's mean S0 agrees to a few percent (render noise; 16 spp over 64 x 48 pixels)."""
    import os
    import subprocess
    import sys

    code = """
import numpy as np
from sim import dataset as sd
from sim.render import render_sample
spec = sd.DatasetSpec(seed=5, defect_fraction=0.0, width=64, height=48, spp=16)
model = sd.prepare(spec)
draw = sd.draw_sample(spec, model, 0)
out = render_sample(model, draw.params, None, spec.render_settings(), draw.mitsuba_seed)
print(float(out.s0.mean()), float(out.s0[out.object_mask].mean()))
"""
    means = {}
    for variant in ("llvm_ad_mono_polarized", "scalar_spectral_polarized"):
        env = {**os.environ, "POLAR_ANO_MI_VARIANT": variant, "PYTHONPATH": os.getcwd()}
        run = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300)
        assert run.returncode == 0, run.stderr[-2000:]
        means[variant] = [float(v) for v in run.stdout.split()[-2:]]
    mono, spectral = means["llvm_ad_mono_polarized"], means["scalar_spectral_polarized"]
    assert spectral[0] == pytest.approx(mono[0], rel=0.05) and spectral[1] == pytest.approx(mono[1], rel=0.05)


def test_a_turned_camera_renders_the_part_turned_about_the_image_centre(variant: str) -> None:
    """``SceneConfig.camera_roll_deg`` = 10: the part's silhouette is the square camera's turned 10 degrees counter-
    clockwise about the image centre (where the camera aims), not clockwise (scipy's positive angle turns an image
    counter-clockwise as shown, row 0 at the top)."""
    from scipy.ndimage import rotate

    model = usb_brick()
    masks = []
    for roll in (0.0, 10.0):
        cfg = SceneConfig(camera_target_jitter_m=0.0, camera_polar_deg=(20.0, 40.0), camera_roll_deg=roll)
        params = sample_scene(np.random.default_rng(5), cfg, model)
        masks.append(render_sample(model, params, None, RenderSettings(width=128, height=96, spp=1), seed=1)
                     .object_mask)
    square, turned = masks

    def iou(a: np.ndarray, b: np.ndarray) -> float:
        return float((a & b).sum() / (a | b).sum())

    ccw, cw = (rotate(square.astype(np.uint8), angle, reshape=False, order=0) > 0 for angle in (10.0, -10.0))
    assert iou(turned, ccw) > 0.9 > iou(turned, square) and iou(turned, ccw) > iou(turned, cw) + 0.1
