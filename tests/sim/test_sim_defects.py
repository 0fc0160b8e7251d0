"""Defect draws: each type is one function of a table, and a seed gives the same defect as before the split."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from sim.defects import (
    _DEFECTS,
    DEFECT_TYPES,
    FACES,
    MOULDING_KINDS,
    NEW_KINDS,
    DefectConfig,
    apply_defect,
    defect_face,
    defect_size,
)
from sim.errors import SimError
from sim.meshes import usb_brick

# Drawn by apply_defect before it became one function per type (seed 7, camera at (0.05, -0.08, 0.25)):
# (record entries drawn, faces of the defect part, faces of the good region or None).
PINNED = {
    "dent": ({"centre_m": [0.004137528, -0.0079, 0.007307671], "radius_mm": 1.4504143799811837,
              "depth_mm": 0.22006651396449017}, 78, 78),
    "scratch": ({"start_m": [0.000922799, -0.0079, 0.006914857], "end_m": [0.007352257, -0.0079, 0.007700484],
                 "length_mm": 6.477279089896511, "width_mm": 0.6500831424556127, "depth_mm": 0.043677672269813096,
                 "alpha": 0.41377723349530227}, 73, 73),
    "stain": ({"centre_m": [0.004137528, -0.0079, 0.007307671], "radius_mm": 1.5630179749764797,
               "darken": 0.2850748282100514, "alpha": 0.4557437058886916}, 65, None),
    "chip": ({"centre_m": [0.015900001, -0.00444375, 0.0096], "size_mm": 1.1280496606787027}, 222, 222),
    "missing_stud": ({"stud": 7, "centre_m": [0.012, 0.004, 0.0113], "radius_mm": 2.4000005796551704}, 148, 436),
}


def test_every_defect_type_has_its_function() -> None:
    assert set(DEFECT_TYPES) == set(PINNED) and set(DEFECT_TYPES) <= set(_DEFECTS)


@pytest.mark.parametrize("kind", DEFECT_TYPES)
def test_a_seed_draws_the_same_defect_as_before(kind: str) -> None:
    model = usb_brick()
    materials = {p.material: {"colour": [0.3, 0.4, 0.5], "alpha": 0.2} for p in model.parts}
    r = apply_defect(model, kind, np.random.default_rng(7), DefectConfig(), np.array([0.05, -0.08, 0.25]), materials)
    drawn, defect_faces, good_faces = PINNED[kind]
    assert list(r.info)[:2] == ["type", "part"] and r.info["type"] == kind and r.info["part"] == "body"
    for key, value in drawn.items():
        np.testing.assert_allclose(r.info[key], value, rtol=1e-9, atol=1e-9, err_msg=key)
    assert r.model.part("defect").faces.shape[0] == defect_faces
    assert (None if r.good_region is None else r.good_region.faces.shape[0]) == good_faces


def test_every_drawn_defect_names_the_face_it_lies_on() -> None:
    model = usb_brick()
    materials = {p.material: {"colour": [0.3, 0.4, 0.5], "alpha": 0.2} for p in model.parts}
    faces = {kind: defect_face({"type": kind, **apply_defect(model, kind, np.random.default_rng(7), DefectConfig(),
                                                             np.array([0.05, -0.08, 0.25]), materials).info})
             for kind in DEFECT_TYPES}
    # the pinned draws: dent, scratch and stain on the face toward the camera (y = -7.9 mm), the chip on the top
    # face's end edge, the stud on the top
    assert faces == {"dent": "front", "scratch": "front", "stain": "front", "chip": "edge", "missing_stud": "top"}
    assert set(faces.values()) <= set(FACES)


def test_an_older_record_without_a_normal_is_on_the_top_face_or_unknown() -> None:
    top = {"type": "scratch", "start_m": [-0.0044, -0.0115, 0.0096], "end_m": [-0.0144, -0.0032, 0.0096]}
    front = {"type": "scratch", "start_m": [-0.0072, -0.0079, -0.0003], "end_m": [-0.0116, -0.0079, 0.0006]}
    assert defect_face(top) == "top" and defect_face(front) is None
    assert defect_face({"type": "stain", "centre_m": [-0.0011, -0.0039, 0.0096]}) == "top"
    assert defect_face({"type": "dent", "normal": [0.0, 1.0, 0.0]}) == "back"
    assert defect_face({"type": "dent", "normal": [-1.0, 0.0, 0.0]}) == "end"
    assert defect_face(None) is None and defect_face({"type": "dent"}) is None
    assert defect_face({"type": "dent", "normal": "up"}) is None


def _draw(kind: str, seed: int = 7):
    model = usb_brick()
    materials = {p.material: {"colour": [0.3, 0.4, 0.5], "alpha": 0.2} for p in model.parts}
    cfg = DefectConfig(types=(kind,))
    return model, apply_defect(model, kind, np.random.default_rng(seed), cfg, np.array([0.05, -0.08, 0.25]), materials)


def test_the_new_kinds_are_not_in_the_default_draw() -> None:
    # every set rendered before them draws the same five kinds
    assert DefectConfig().types == DEFECT_TYPES == ("dent", "scratch", "stain", "chip", "missing_stud")
    assert set(NEW_KINDS) == {"blister", "debris"} and not set(NEW_KINDS) & set(DEFECT_TYPES)
    assert set(MOULDING_KINDS) == {"sink", "short_shot", "warp", "flash"}
    assert not set(MOULDING_KINDS) & set(DEFECT_TYPES)
    assert set(_DEFECTS) == set(DEFECT_TYPES) | set(NEW_KINDS) | set(MOULDING_KINDS)
    with pytest.raises(SimError, match="unknown"):
        DefectConfig(types=("bubble",))


def test_a_blister_pushes_the_face_out_where_a_dent_pushes_it_in() -> None:
    _, b = _draw("blister")
    _, d = _draw("dent")

    def out_and_in_mm(r) -> tuple[float, float]:  # how far the defect's faces lie out of and into the face
        h = (r.model.part("defect").vertices.astype(np.float64) - r.info["centre_m"]) @ np.asarray(r.info["normal"])
        return h.max() * 1000, -h.min() * 1000

    (b_out, b_in), (d_out, d_in) = out_and_in_mm(b), out_and_in_mm(d)
    # the same draw's place: the blister rises by its height, the dent sinks by its depth (up to where the mesh's
    # 0.5 mm grid samples the profile's top)
    assert b.info["centre_m"] == d.info["centre_m"] and b.info["normal"] == d.info["normal"]
    assert 0.8 * b.info["height_mm"] < b_out <= b.info["height_mm"] + 1e-6 and b_in < 1e-6
    assert 0.8 * d.info["depth_mm"] < d_in <= d.info["depth_mm"] + 1e-6 and d_out < 1e-6
    assert 1.0 <= b.info["radius_mm"] <= 2.5 and 0.05 <= b.info["height_mm"] <= 0.3
    assert b.good_region is not None and defect_face({"type": "blister", **b.info}) == "front"


def test_debris_is_a_matte_particle_resting_on_a_face() -> None:
    model, r = _draw("debris")
    particle = r.model.part("defect")
    c, n = np.asarray(r.info["centre_m"]), np.asarray(r.info["normal"])
    radius = r.info["radius_mm"] / 1000
    assert 0.15 <= r.info["radius_mm"] <= 0.5 and 0.05 <= r.info["grey"] <= 0.9
    h = (particle.vertices.astype(np.float64) - c) @ n
    # it sits on the face: its lowest point a little below it (contact), its top one diameter up at most
    assert -0.5 * radius < h.min() < 0 and h.max() < 2 * radius
    # the part itself is unchanged: the body keeps every face, nothing disappeared (no good region)
    assert r.model.part("body").faces.shape == model.part("body").faces.shape and r.good_region is None
    assert r.material == {"type": "diffuse", "colour": [r.info["grey"]] * 3}
    assert defect_face({"type": "debris", **r.info}) == "front"
    # seeded
    assert _draw("debris")[1].info == r.info and _draw("debris", 8)[1].info != r.info


def test_a_sink_mark_is_a_broad_shallow_dent() -> None:
    _, r = _draw("sink")
    assert r.good_region is not None
    # each vertex of the region moved in along the face's normal, the deepest by the depth
    moved = r.model.part("defect").vertices.astype(np.float64) - r.good_region.vertices
    h = moved @ np.asarray(r.info["normal"]) * 1000
    assert 2.5 <= r.info["radius_mm"] <= 5.0 and 0.02 <= r.info["depth_mm"] <= 0.1
    assert 0.8 * r.info["depth_mm"] < -h.min() <= r.info["depth_mm"] + 1e-6 and h.max() < 1e-6
    name, slope = defect_size({"type": "sink", **r.info})
    assert name == "slope_deg" and 0.3 < slope < 3.7


def test_a_short_shot_is_a_stud_not_filled_to_its_top() -> None:
    model, r = _draw("short_shot")
    full, short = model.part("studs"), r.model.part("defect")
    base = float(model.part("body").vertices[:, 2].max())
    top = float(full.vertices[:, 2].max())
    # the short stud rises the filled share of a full one, from the body's top; the other seven are whole
    np.testing.assert_allclose(short.vertices[:, 2].max() - base, r.info["fill"] * (top - base), rtol=1e-4)
    assert 0.3 <= r.info["fill"] <= 0.8 and r.model.part("studs").faces.shape[0] == full.faces.shape[0] * 7 // 8
    np.testing.assert_allclose(r.info["short_mm"], (1 - r.info["fill"]) * 1.7, rtol=1e-3)
    # the good region is the full stud, where it stood
    assert r.good_region is not None and float(r.good_region.vertices[:, 2].max()) == top
    assert defect_face({"type": "short_shot", **r.info}) == "top"
    assert defect_size({"type": "short_shot", **r.info}) == ("short_mm", r.info["short_mm"])


@pytest.mark.parametrize("seed", [7, 8])
def test_a_warp_bows_the_whole_part_which_still_rests_on_the_belt(seed: int) -> None:
    model, r = _draw("warp", seed)
    sag = r.info["sag_mm"] / 1000
    body, bowed = model.part("body"), r.model.part("defect")
    assert 0.1 <= abs(r.info["sag_mm"]) <= 0.5 and bowed.faces.shape == body.faces.shape
    lift = bowed.vertices[:, 2].astype(np.float64) - body.vertices[:, 2]
    middle, ends = np.abs(body.vertices[:, 0]) < 1e-4, np.abs(body.vertices[:, 0]) > 0.0158
    # bowed up (sag > 0) the middle rises by the sag, the ends stay; bowed down the ends rise by it
    np.testing.assert_allclose(lift[middle].mean() - lift[ends].mean(), sag, atol=2e-6)
    assert abs(lift.min()) < 1e-6 and bowed.vertices[:, 2].min() == pytest.approx(0.0, abs=1e-6)
    # studs and plug move with it; the shading normals turn with the surface (top face's normal tilts at the ends)
    assert not np.allclose(r.model.part("studs").vertices, model.part("studs").vertices)
    up = (body.normals[:, 2] > 0.99) & ends
    tilt = np.degrees(np.arccos(np.clip(bowed.normals[up, 2], -1, 1)))
    np.testing.assert_allclose(tilt, np.degrees(np.arctan(4 * abs(sag) / 0.0318)), rtol=1e-3)
    assert r.good_region is not None and r.good_region.faces.shape == body.faces.shape
    assert defect_face({"type": "warp", **r.info}) == "top"
    assert defect_size({"type": "warp", **r.info}) == ("sag_mm", abs(r.info["sag_mm"]))


@pytest.mark.parametrize("seed", [3, 7, 11, 19])
def test_flash_is_a_thin_fin_out_of_a_side_face_at_its_top_or_bottom_edge(seed: int) -> None:
    model, r = _draw("flash", seed)
    body = model.part("body").vertices.astype(np.float64)
    lo, hi = body.min(0), body.max(0)
    fin = r.model.part("defect").vertices.astype(np.float64)
    n = np.asarray(r.info["normal"])
    axis = int(np.flatnonzero(n)[0])
    face = hi[axis] if n[axis] > 0 else lo[axis]
    out = (fin[:, axis] - face) * n[axis]  # how far the fin reaches out of its face: its width, and 0.5 mm in
    mm = {"abs": 1e-4}  # the part's vertices are float32
    assert out.max() * 1000 == pytest.approx(r.info["width_mm"], **mm) and out.min() * 1000 == pytest.approx(-0.5, **mm)
    assert (np.ptp(fin[:, 2]) * 1000 == pytest.approx(r.info["thickness_mm"], **mm)
            and np.ptp(fin[:, 1 - axis]) * 1000 == pytest.approx(r.info["length_mm"], **mm))
    # within the top or the bottom plane (never on it: no two faces at one place), and along the face's edge
    if r.info["edge"] == "top":
        assert hi[2] - 2e-5 < fin[:, 2].max() < hi[2]
    else:
        assert lo[2] < fin[:, 2].min() < lo[2] + 2e-5
    assert lo[1 - axis] - 1e-9 <= fin[:, 1 - axis].min() and fin[:, 1 - axis].max() <= hi[1 - axis] + 1e-9
    assert 0.05 <= r.info["thickness_mm"] <= 0.2 and 0.2 <= r.info["width_mm"] <= 1.0
    # the camera at (0.05, -0.08, 0.25) sees the -y and +x faces: the fin is on one of them
    assert (axis, n[axis]) in ((1, -1.0), (0, 1.0)) and defect_face({"type": "flash", **r.info}) in ("front", "end")
    # the part is unchanged (nothing disappeared) and the fin is its plastic
    assert r.good_region is None and r.material == {"colour": [0.3, 0.4, 0.5], "alpha": 0.2}
    assert defect_size({"type": "flash", **r.info}) == ("area_mm2", pytest.approx(r.info["width_mm"]
                                                                                  * r.info["length_mm"]))
    assert _draw("flash", seed)[1].info == r.info  # seeded


def test_a_part_without_studs_draws_no_short_shot() -> None:
    plain = dataclasses.replace(usb_brick(), features=())
    assert DefectConfig(types=("short_shot", "sink")).usable_types(plain) == ("sink",)
    assert DefectConfig(types=("short_shot", "sink")).usable_types(usb_brick()) == ("short_shot", "sink")
