"""Scene randomisation ranges (SceneConfig): the fixed-station keys and the draws of sets rendered before them."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

from sim.dataset import DatasetSpec
from sim.errors import SimError
from sim.meshes import usb_brick
from sim.scene import SceneConfig, camera_axes, sample_scene

LINE_PRESET = Path(__file__).resolve().parents[2] / "sim" / "presets" / "line.toml"


def test_default_ranges_draw_what_earlier_sets_drew() -> None:
    # Values drawn by the code before yaw, azimuth, rest pose and ground colour became ranges (commit d332253):
    # a set rendered then must be reproduced sample for sample.
    p = sample_scene(np.random.default_rng([0, 5]), SceneConfig(), usb_brick())
    assert p["pose"]["index"] == 1
    assert p["pose"]["yaw_rad"] == pytest.approx(3.4416088468621964, rel=1e-12)
    np.testing.assert_allclose(p["camera"]["origin"], [-0.3807002291301368, 0.09562077037936681, 0.2518675106759474],
                               rtol=1e-12)
    np.testing.assert_allclose(p["light"]["origin"], [0.033997148190859916, -0.9886159498341112, 0.7111364266042016],
                               rtol=1e-12)
    np.testing.assert_allclose(p["background"]["colour2"], [0.44200728163291403, 0.8735617179369904,
                                                            0.7009057180555119], rtol=1e-12)


FIRST_V2_SCENE_KEYS = {"alpha_rough", "alpha_smooth", "ambient_radiance", "background_size_m", "backgrounds",
                       "camera_polar_deg", "camera_radius_m", "camera_target_jitter_m", "colour", "focal_length_mm",
                       "light_cutoff_deg", "light_intensity", "light_polar_deg", "light_radius_m", "max_depth",
                       "object_xy_m", "sensor_width_mm"}
"""The [scene] keys of renderer version 2's first sets' manifests: every key added since must stay out at its
default (the ring light's keys did not, so every set rendered before them refused to resume)."""


def test_default_manifest_has_no_new_keys() -> None:
    # Resuming a set compares manifests: keys at their defaults stay out, so older sets still resume.
    scene = DatasetSpec().to_dict()["scene"]
    assert set(scene) == FIRST_V2_SCENE_KEYS
    line = DatasetSpec.from_dict({"scene": {"rest_pose": 0}}).to_dict()["scene"]
    assert line["rest_pose"] == 0


def test_gradient_dome_is_in_the_sample_only_when_set() -> None:
    # a sample's parameters are its record: older samples (no key) render as the uniform dome they were
    plain = sample_scene(np.random.default_rng(0), SceneConfig(), usb_brick())
    graded = sample_scene(np.random.default_rng(0), SceneConfig(ambient_gradient=0.8), usb_brick())
    assert "ambient_gradient" not in plain and graded.pop("ambient_gradient") == 0.8
    assert json.dumps(graded, sort_keys=True) == json.dumps(plain, sort_keys=True)  # no draw changes
    flipped = sample_scene(np.random.default_rng(0),
                           SceneConfig(ambient_gradient=0.8, ambient_gradient_azimuth_deg=180.0), usb_brick())
    assert flipped.pop("ambient_gradient_azimuth_deg") == 180.0 and flipped.pop("ambient_gradient") == 0.8
    assert json.dumps(flipped, sort_keys=True) == json.dumps(plain, sort_keys=True)  # the same part, pose and draws


def test_line_preset_fixes_pose_orientation_and_ground() -> None:
    scene = tomllib.loads(LINE_PRESET.read_text())["scene"]
    cfg = SceneConfig.from_dict(scene)
    model = usb_brick()
    for i in range(40):
        p = sample_scene(np.random.default_rng([0, i]), cfg, model)
        assert p["pose"]["index"] == 0
        assert -5 <= np.degrees(p["pose"]["yaw_rad"]) <= 5
        target, cam, light = (np.asarray(x) for x in (p["camera"]["target"], p["camera"]["origin"],
                                                       p["light"]["origin"]))
        d = cam - target
        polar = np.degrees(np.arccos(d[2] / np.linalg.norm(d)))
        azimuth = np.degrees(np.arctan2(d[1], d[0])) % 360
        assert 29.5 <= polar <= 35.5 and 264 <= azimuth <= 276  # target jitter 1 mm at 0.39 m
        assert np.degrees(np.arctan2(*(light - target)[1::-1])) % 360 == pytest.approx(90, abs=6)
        assert camera_axes(p["camera"])[1][1] > 0.8  # image up is world +y: the part lies the same way in every frame
        assert p["background"]["kind"] == "plain"
        assert all(0.05 <= c <= 0.15 for c in p["background"]["colour2"] + p["background"]["material"]["colour"])


@pytest.mark.parametrize(("key", "value", "words"), [
    ("rest_pose", 99, "rest_pose: 99"),
    ("rest_pose", -2, "scene.rest_pose"),
    ("background_colour", (0.5, 1.5), "scene.background_colour"),
    ("yaw_deg", (10.0, -10.0), "scene.yaw_deg"),
    ("ambient_gradient", 1.5, "scene.ambient_gradient"),
    ("ambient_gradient", -0.5, "scene.ambient_gradient"),
    ("ambient_gradient_azimuth_deg", 360.0, "scene.ambient_gradient_azimuth_deg"),
    ("ambient_gradient_azimuth_deg", -90.0, "scene.ambient_gradient_azimuth_deg"),
])
def test_bad_ranges_name_the_key(key: str, value, words: str) -> None:
    with pytest.raises(SimError, match=words):
        sample_scene(np.random.default_rng(0), SceneConfig(**{key: value}), usb_brick())


def test_line_polar_preset_is_the_line_at_brewster_under_a_dome() -> None:
    """sim/presets/line-polar.toml (the visibility study's choice) keeps the line's fixture and belt and changes
    only the camera's elevation, the light and the bit depth."""
    from sim.dataset import read_overrides

    polar, line = read_overrides(LINE_PRESET.with_name("line-polar.toml")), read_overrides(LINE_PRESET)
    changed = {k for k in set(polar["scene"]) | set(line["scene"]) if polar["scene"].get(k) != line["scene"].get(k)}
    assert changed == {"camera_polar_deg", "light_intensity", "ambient_radiance"}
    assert polar["scene"]["camera_polar_deg"][0] < np.degrees(np.arctan(1.5)) < polar["scene"]["camera_polar_deg"][1]
    assert polar["sensor"] == {"bit_depth": 12, "exposure_gain": 2.0}


def test_brick_materials_override_keeps_the_draws() -> None:
    # `station render --materials` on the brick: the same parts and draws, another microfacet model on the plastic
    from sim.meshes import object_from_config
    from sim.scene import material_keys_check
    from sim.variant import set_variant

    set_variant()
    ggx = object_from_config(None, {"plastic": {"type": "pplastic", "finish": "smooth", "distribution": "ggx"}})
    material_keys_check(ggx)
    plain = sample_scene(np.random.default_rng(3), SceneConfig(), usb_brick())
    other = sample_scene(np.random.default_rng(3), SceneConfig(), ggx)
    assert other["materials"]["plastic"].pop("distribution") == "ggx"
    assert json.dumps(other, sort_keys=True) == json.dumps(plain, sort_keys=True)
    assert "distribution" not in usb_brick().materials["plastic"]  # the cached brick is not changed
    with pytest.raises(SimError, match="material keys"):
        object_from_config(None, {"body": "pplastic"})
    with pytest.raises(SimError, match="'plastic'"):
        material_keys_check(object_from_config(None, {"plastic": {"type": "pplastic", "distribution": "ggz"}}))


def test_finish_vary_preset_widens_only_the_plastics_roughness() -> None:
    """sim/presets/finish-vary.toml (rule 62): layered after the line's presets, each part keeps every draw but the
    smooth plastic's roughness alpha, which comes from the same random number mapped onto [0.001, 0.03] instead of
    the preset's [0.001, 0.011]."""
    from sim.dataset import read_layers

    presets = LINE_PRESET.parent
    line = [presets / f"{name}.toml" for name in ("line-polar", "variation", "panel", "panel-vary")]
    built = SceneConfig.from_dict(read_layers(line)["scene"])
    wide = SceneConfig.from_dict(read_layers([*line, presets / "finish-vary.toml"])["scene"])
    assert (built.alpha_smooth, wide.alpha_smooth) == ((0.001, 0.011), (0.001, 0.03))
    alphas = []
    for seed in range(20):
        a = sample_scene(np.random.default_rng([101, seed]), built, usb_brick())
        b = sample_scene(np.random.default_rng([101, seed]), wide, usb_brick())
        ka, kb = a["materials"]["plastic"].pop("alpha"), b["materials"]["plastic"].pop("alpha")
        assert json.dumps(a, sort_keys=True) == json.dumps(b, sort_keys=True)
        assert (kb - 0.001) == pytest.approx((ka - 0.001) * 0.029 / 0.010, rel=1e-9)
        alphas.append(kb)
    assert max(alphas) > 0.011  # the wider range is drawn, not just allowed


def test_chamfered_brick_is_closed_and_keeps_the_line_s_draws() -> None:
    """`edge_mm`: the body's edges cut at 45 degrees; the same parts, poses and lights as the sharp brick's."""
    import trimesh

    from sim.meshes import chamfered_box_mesh, object_from_config

    size, c = np.array([0.0318, 0.0158, 0.0096]), 0.0003
    v, f = chamfered_box_mesh(np.zeros(3), size, c, 0.0005)
    closed = trimesh.Trimesh(v, f, process=True)  # vertices merged: the pieces meet without cracks
    assert closed.is_watertight and closed.is_winding_consistent
    cut = 4 * (c * c / 2) * (size - 2 * c).sum()  # the twelve strips' prisms (the corners are smaller still)
    assert closed.volume == pytest.approx(size.prod() - cut, rel=1e-3)  # positive: normals point out
    line = SceneConfig.from_dict({"rest_pose": 0})
    sharp = sample_scene(np.random.default_rng([7, 1]), line, usb_brick())
    chamfered = sample_scene(np.random.default_rng([7, 1]), line, usb_brick(0.5, 0.3))
    for d in (sharp, chamfered):
        d["pose"].pop("probability")  # the resting poses' odds follow the hull, a little
    a, b = _leaves(sharp), _leaves(chamfered)
    assert a.keys() == b.keys()
    for key, value in a.items():  # positions within 0.2 mm: the aim follows the centre of the part's vertices
        assert value == b[key] if isinstance(value, str) else np.allclose(value, b[key], atol=2e-4, rtol=0), key
    assert "edge_mm" not in DatasetSpec().to_dict() and DatasetSpec(edge_mm=0.3).to_dict()["edge_mm"] == 0.3
    with pytest.raises(SimError, match=r"edge_mm must be a number or a range \[lo, hi\] in \[0, 2\]"):
        DatasetSpec(edge_mm=3.0)
    with pytest.raises(SimError, match=r"edge_mm must be a number or a range"):
        DatasetSpec(edge_mm=(0.4, 0.1))
    with pytest.raises(SimError, match=r"edge_mm: 0\.4 chamfers the brick.s edges; the mesh part\.ply brings its own"):
        DatasetSpec(mesh="part.ply", edge_mm=(0.0, 0.4))  # before anything renders, not on the first drawn part
    with pytest.raises(SimError, match=r"edge_mm: 0\.3 chamfers the brick.s edges; the mesh part\.ply brings its own"):
        object_from_config("part.ply", None, edge_mm=0.3)


def test_rounded_brick_is_closed_smooth_and_refuses_chips() -> None:
    """`edge_shape = "round"`: a fillet of the radius, closed, of the right volume, shaded smooth; a chip needs a
    crease, so a set of round edges that would draw chips is refused before anything renders."""
    import trimesh

    from sim.defects import DefectConfig
    from sim.meshes import rounded_box_mesh

    size, r = np.array([0.0318, 0.0158, 0.0096]), 0.0003
    v, f, n = rounded_box_mesh(np.zeros(3), size, r, 0.0005)
    closed = trimesh.Trimesh(v, f, process=True)
    assert closed.is_watertight and closed.is_winding_consistent
    a, b, c = size / 2 - r  # Steiner: the inner box grown by a ball of radius r
    exact = 8 * a * b * c + 8 * (a * b + b * c + c * a) * r + 2 * np.pi * (a + b + c) * r * r + 4 / 3 * np.pi * r**3
    assert closed.volume == pytest.approx(exact, rel=1e-4) and closed.volume < size.prod() - 1e-9
    assert np.allclose(np.linalg.norm(n, axis=1), 1)
    geo = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    assert (np.einsum("ij,ij->i", geo, n[f].sum(1)) > 0).all()  # shading normals on the faces' outer side
    key = np.round(v / 1e-7).astype(np.int64)  # where pieces meet, their normals agree: no crease anywhere
    _, group = np.unique(key, axis=0, return_inverse=True)
    mean = np.zeros((group.max() + 1, 3))
    np.add.at(mean, group.ravel(), n)
    assert (np.linalg.norm(mean / np.bincount(group.ravel())[:, None], axis=1) > 0.999).all()
    brick = usb_brick(0.5, 0.3, "round")
    assert len(brick.part("body").vertices) == len(v) and brick is not usb_brick(0.5, 0.3)
    line = SceneConfig.from_dict({"rest_pose": 0})  # the sharp brick's pose, light and camera, not turned about z
    sharp, rounded = (_leaves(sample_scene(np.random.default_rng([7, 1]), line, m)) for m in (usb_brick(), brick))
    assert sharp.keys() == rounded.keys()
    for k, value in sharp.items():  # the aim follows the centre of the part's vertices, within 0.2 mm
        assert value == rounded[k] if isinstance(value, str) else np.allclose(value, rounded[k], atol=2e-4, rtol=0), k
    with pytest.raises(SimError, match="edge shape 'oval'"):
        usb_brick(0.5, 0.3, "oval")
    assert DatasetSpec(edge_mm=0.3, edge_shape="round", defect_fraction=0.0).to_dict()["edge_shape"] == "round"
    assert "edge_shape" not in DatasetSpec(edge_mm=0.3).to_dict()
    with pytest.raises(SimError, match="edge_shape round: a chip cuts a crease"):
        DatasetSpec(edge_mm=0.3, edge_shape="round")
    spec = DatasetSpec(edge_mm=0.3, edge_shape="round", defects=DefectConfig(types=("dent", "stain")))
    assert DatasetSpec.from_dict(spec.to_dict()) == spec
    with pytest.raises(SimError, match="edge_shape must be one of chamfer, round"):
        DatasetSpec(edge_mm=0.3, edge_shape="fillet")


def test_a_range_of_edges_is_drawn_per_part_on_its_own_stream() -> None:
    """`--edge-mm 0,0.4`: each part's chamfer drawn to 0.01 mm; every other draw as with sharp edges."""
    from sim.dataset import draw_sample, generate_sample, prepare

    line = {"scene": {"rest_pose": 0}, "defect_fraction": 0.0, "seed": 7}
    sharp_spec = DatasetSpec.from_dict(line)
    ranged = DatasetSpec.from_dict({**line, "edge_mm": [0.0, 0.4]})
    assert ranged.to_dict()["edge_mm"] == [0.0, 0.4] and DatasetSpec.from_dict({"edge_mm": 0.3}).edge_mm == (0.3, 0.3)
    sharp_model, ranged_model = prepare(sharp_spec), prepare(ranged)
    edges = []
    for i in range(6):
        a, b = draw_sample(sharp_spec, sharp_model, i), draw_sample(ranged, ranged_model, i)
        assert a.edge_mm is None and b.edge_mm is not None and 0.0 <= b.edge_mm <= 0.4
        assert b.edge_mm == round(b.edge_mm, 2) and draw_sample(ranged, ranged_model, i).part is b.part
        a.params["pose"].pop("probability"), b.params["pose"].pop("probability")
        la, lb = _leaves(a.params), _leaves(b.params)
        assert la.keys() == lb.keys() and a.mitsuba_seed == b.mitsuba_seed
        for key, value in la.items():
            assert value == lb[key] if isinstance(value, str) else np.allclose(value, lb[key], atol=2e-4, rtol=0)
        edges.append(b.edge_mm)
    assert len(set(edges)) > 3
    tiny = DatasetSpec.from_dict({**line, "edge_mm": [0.1, 0.3], "width": 64, "height": 48, "spp": 1,
                                  "ground_truth": False})
    sample = generate_sample(tiny, prepare(tiny), 0)
    assert sample.params["edge_mm"] == draw_sample(tiny, prepare(tiny), 0).edge_mm


def _leaves(d: dict, prefix: str = "") -> dict:
    """A nested scene dict's leaves by their path."""
    out = {}
    for k, v in d.items():
        out.update(_leaves(v, f"{prefix}{k}/") if isinstance(v, dict) else {f"{prefix}{k}": v})
    return out


def test_render_command_takes_the_edge_shape(tmp_path, capsys) -> None:
    """`station render --edge-mm 0.3 --edge-shape round`: into the set's spec; with the default types (chips among
    them) one line naming the key, before anything renders."""
    from station.cli import build_parser, main
    from station.commands.render import build_spec

    types = tmp_path / "no-chips.toml"
    types.write_text('[defects]\ntypes = ["dent", "stain"]\n')
    args = build_parser().parse_args(["render", "--out", str(tmp_path / "x"), "--count", "1", "--edge-mm", "0.3",
                                      "--edge-shape", "round", "--config", str(types)])
    spec = build_spec(args)
    assert spec.edge_shape == "round" and spec.edge_mm == (0.3, 0.3) and spec.to_dict()["edge_shape"] == "round"
    chamfer = build_parser().parse_args(["render", "--out", "x", "--count", "1", "--edge-mm", "0.3"])
    assert build_spec(chamfer).edge_shape == "chamfer"
    code = main(["render", "--out", str(tmp_path / "y"), "--edge-mm", "0.3", "--edge-shape", "round", "--count", "1"])
    err = capsys.readouterr().err.strip()
    assert code != 0 and len(err.splitlines()) == 1 and "edge_shape round: a chip cuts a crease" in err, err
    assert not (tmp_path / "y").exists()


def test_a_share_of_parts_draws_a_ggx_lobe_on_its_own_stream() -> None:
    """`[scene] ggx_share`: that share of parts has every microfacet material's lobe GGX instead of Beckmann, drawn
    on the part's own stream; every other draw as without it; a render takes the lobe; the manifest of a set
    without it is as before; a share outside [0, 1] is refused naming the key."""
    from sim.dataset import draw_sample, generate_sample, prepare
    from sim.scene import bsdf_dict

    line = {"scene": {"rest_pose": 0}, "defect_fraction": 0.0, "seed": 7}
    plain = DatasetSpec.from_dict(line)
    mixed = DatasetSpec.from_dict({**line, "scene": {"rest_pose": 0, "ggx_share": 0.5}})
    assert "ggx_share" not in plain.to_dict()["scene"] and mixed.to_dict()["scene"]["ggx_share"] == 0.5
    model = prepare(plain)
    lobes = []
    for i in range(12):
        a, b = draw_sample(plain, model, i), draw_sample(mixed, model, i)
        ggx = [m for m in b.params["materials"].values() if m.get("distribution") == "ggx"]
        assert not any("distribution" in m for m in a.params["materials"].values())
        assert ggx == [] or len(ggx) == sum(m["type"] in ("pplastic", "roughconductor")
                                            for m in b.params["materials"].values())
        assert all(bsdf_dict(m)["distribution"] == "ggx" for m in ggx)
        for m in b.params["materials"].values():
            m.pop("distribution", None)
        assert a.params == b.params and a.mitsuba_seed == b.mitsuba_seed
        lobes.append(bool(ggx))
    assert 0 < sum(lobes) < 12
    tiny = DatasetSpec.from_dict({**mixed.to_dict(), "width": 64, "height": 48, "spp": 1, "ground_truth": False})
    first = lobes.index(True)
    sample = generate_sample(tiny, prepare(tiny), first)
    assert any(m.get("distribution") == "ggx" for m in sample.params["scene"]["materials"].values())
    with pytest.raises(SimError, match="ggx_share"):
        SceneConfig(ggx_share=1.5)


def test_a_turned_camera_keeps_every_draw_and_turns_the_scene_counter_clockwise_in_the_image() -> None:
    """``camera_roll_deg``: a camera mounted out of square. Only its up direction changes (no draw: the same parts
    and poses as the square line), and a point the square camera sees at image right is seen turned by the roll,
    counter-clockwise (image up at the top)."""
    square = sample_scene(np.random.default_rng(3), SceneConfig(), usb_brick())
    turned = sample_scene(np.random.default_rng(3), SceneConfig(camera_roll_deg=5.0), usb_brick())
    right = camera_axes(square["camera"])[0]  # world direction of the square image's right
    x, y, z = camera_axes(turned["camera"]) @ right
    assert np.degrees(np.arctan2(y, x)) == pytest.approx(5.0) and z == pytest.approx(0.0, abs=1e-12)
    assert turned["camera"].pop("up") != square["camera"].pop("up")
    assert json.dumps(turned, sort_keys=True) == json.dumps(square, sort_keys=True)
    assert SceneConfig(camera_roll_deg=-3.0).camera_roll_deg == -3.0  # either way
    assert "camera_roll_deg" not in DatasetSpec().to_dict()["scene"]
