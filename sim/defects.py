"""Physically rendered defects with pixel-exact masks.

A defect changes the object's geometry or material on a region of its body and moves that region into its own
part named ``defect`` (own Mitsuba shape): the defect mask is then where that shape is visible in a 1-spp
shape-index pass (``sim.render``). For defects that change geometry, the region of the *good* object (before
the change, e.g. the stud that is now missing) is also kept: its visible pixels in the good scene join the
mask, so material that disappeared counts too. A defect on a side facing away, under the object or hidden
behind another part gives an empty mask, and the sample is labelled good.

Types (sizes in millimetres, drawn uniformly from ``DefectConfig`` ranges):
  dent          smooth cosine-profile depression (radius, depth) pushed along the face normal
  scratch       a line (length, width) of rougher material (alpha), optionally a shallow groove (depth)
  stain         a disc (radius) of darker, rougher material (contamination)
  chip          a sharp edge or corner cut off by a plane (size = cut depth along the edge's bisector)
  missing_stud  one stud of the brick removed (objects with studs only)
Kinds drawn only when a set names them (``[defects] types``; ``NEW_KINDS``, not in the default draw, so every set
rendered before them draws the same), for measuring what a model does on a kind nobody rendered before:
  blister       the dent's profile pushed *out* of the face (radius, height): a raised bump, convex where a dent
                is concave (gas trapped under a moulded skin)
  debris        a matte particle resting on a face (radius, grey level): a sphere of ``diffuse`` material (dust, a
                flake of something else); it adds material and changes nothing of the part
Moulding kinds, likewise drawn only when named (``MOULDING_KINDS``): what an injection-moulded part goes wrong with,
for a second look at kinds nobody rendered (docs/results/2026-12-05-moulding-kinds.md):
  sink          a sink mark: the dent's profile, broad and shallow (radius, depth), where a thick section shrank
  short_shot    a stud not filled to its top (filled share of its height): the stud shorter, its top lower
  warp          the whole part bowed along its length (sag: + the middle up, - the ends up), studs and plug with
                it; the part rests on the belt as bowed; the whole body is the defect
  flash         a thin fin of the part's own plastic sticking straight out of a side face along part of its top or
                bottom edge, where a mould's halves meet (thickness, width out of the face, length along the edge)
Each type is one function (``_dent``, ``_scratch``, ...; the table ``_DEFECTS``) that ``apply_defect`` dispatches to.
Deformations are functions of position applied to all body vertices, so the duplicated vertices along sharp
edges move together and the surface never cracks.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import asdict, dataclass, fields
from typing import Any

import numpy as np

from .errors import SimError
from .meshes import ObjectModel, Part, box_mesh, face_normals, vertex_normals

DEFECT_TYPES = ("dent", "scratch", "stain", "chip", "missing_stud")
"""The kinds a set draws by default (``DefectConfig.types``) and that models are trained and evaluated on."""
NEW_KINDS = ("blister", "debris")
"""Kinds drawn only when a set names them: for evaluating a model on kinds nobody trained or chose anything on."""
MOULDING_KINDS = ("sink", "short_shot", "warp", "flash")
"""Moulding defects, drawn only when a set names them (``sim/presets/moulding-kinds.toml``), as ``NEW_KINDS``."""
DEFECT_PART = "defect"


def defect_size(defect: dict[str, Any] | None) -> tuple[str, float] | None:
    """(name, value) of the one physical size that governs how visible a rendered defect is, from ``params.json``'s
    ``defect`` record; None for a good part, a missing stud (all alike) or a record without the fields.

    - dent: ``slope_deg``, its steepest tilt, atan(pi/2 * depth / radius) in degrees (the cosine profile's largest
      slope): what turns a mirrored light or the shading away;
    - scratch: ``area_mm2``, length x width: the rough stripe that scatters a mirrored light away;
    - stain: ``radius_mm``;
    - chip: ``size_mm``, the cut's depth along the edge's bisector;
    - blister, sink: ``slope_deg``, as a dent's (their profile is a dent's, raised or shallow);
    - debris: ``radius_mm``, the particle's;
    - short_shot: ``short_mm``, how far the stud's top lies below a full stud's;
    - warp: ``sag_mm``, the bow's size (either sign);
    - flash: ``area_mm2``, the fin's width out of the face x its length: what it adds to the part's outline."""
    if not defect:
        return None
    kind = defect.get("type")
    try:
        if kind in ("dent", "blister", "sink"):
            rise = defect["height_mm"] if kind == "blister" else defect["depth_mm"]
            return "slope_deg", float(np.degrees(np.arctan(np.pi / 2 * rise / defect["radius_mm"])))
        if kind in ("scratch", "flash"):
            return "area_mm2", float(defect["length_mm"] * defect["width_mm"])
        if kind in ("stain", "debris"):
            return "radius_mm", float(defect["radius_mm"])
        if kind == "chip":
            return "size_mm", float(defect["size_mm"])
        if kind == "short_shot":
            return "short_mm", float(defect["short_mm"])
        if kind == "warp":
            return "sag_mm", abs(float(defect["sag_mm"]))
    except (KeyError, TypeError, ZeroDivisionError):
        return None
    return None


FACES = ("top", "front", "back", "end", "bottom", "edge")
"""The faces ``defect_face`` names, in the part's frame (x along the part, y across it, z up): top (+z), front (-y:
the side both line presets' cameras look from, ``camera_azimuth_deg`` about 270), back (+y), end (+-x), bottom
(-z), and edge (between two faces: a chip's cut, whose normal is their bisector)."""

LEGACY_TOP_MM = 9.5
"""Records written before 2026-12-01 carry no normal for a scratch or a stain: one whose middle lies at least this
high (the built-in brick's top face is at 9.6 mm; a face below it has its picked centre lower) is on the top face,
others unknown."""


def defect_face(defect: dict[str, Any] | None) -> str | None:
    """The face of the part a rendered defect lies on (``FACES``), from ``params.json``'s ``defect`` record: by the
    recorded surface normal (within 25 deg of a face's), a missing or short stud on the top, a warp on the top (the
    face that shows a bow most: it tilts the top face's mirror image); None for a good part or a record without the
    fields (an older scratch or stain off the top face: ``LEGACY_TOP_MM``)."""
    if not defect:
        return None
    if defect.get("type") in ("missing_stud", "short_shot", "warp"):
        return "top"
    try:
        n = defect.get("normal")
        if n is None:
            z = (float(defect["centre_m"][2]) if "centre_m" in defect  # a scratch's middle lies on its face
                 else (float(defect["start_m"][2]) + float(defect["end_m"][2])) / 2)
            return "top" if z * 1000 >= LEGACY_TOP_MM else None
        x, y, z = (float(v) for v in n)
    except (KeyError, TypeError, ValueError, IndexError):
        return None
    for face, ok in (("top", z > 0.9), ("bottom", z < -0.9), ("front", y < -0.9), ("back", y > 0.9),
                     ("end", abs(x) > 0.9)):
        if ok:
            return face
    return "edge"


def apparent_size(defect: dict[str, Any] | None) -> tuple[str, float] | None:
    """("visible_px", the defect's pixels in the rendered frame: its mask's area, what the camera gives a detector
    of it, whatever its type; a defect on a face seen at a grazing angle or partly hidden has few) from
    ``params.json``'s ``defect`` record; None for a good part or a record without it."""
    px = (defect or {}).get("visible_px")
    return None if px is None else ("visible_px", float(px))


@dataclass(frozen=True)
class DefectConfig:
    types: tuple[str, ...] = DEFECT_TYPES
    dent_radius_mm: tuple[float, float] = (1.0, 3.0)
    dent_depth_mm: tuple[float, float] = (0.1, 0.5)
    scratch_length_mm: tuple[float, float] = (4.0, 15.0)
    scratch_width_mm: tuple[float, float] = (0.5, 1.0)
    scratch_alpha: tuple[float, float] = (0.25, 0.6)
    scratch_depth_mm: tuple[float, float] = (0.0, 0.05)
    stain_radius_mm: tuple[float, float] = (1.0, 3.5)
    stain_darken: tuple[float, float] = (0.15, 0.6)
    """Factor on the material colour inside the stain."""
    stain_alpha: tuple[float, float] = (0.15, 0.5)
    chip_size_mm: tuple[float, float] = (0.5, 1.2)
    blister_radius_mm: tuple[float, float] = (1.0, 2.5)
    blister_height_mm: tuple[float, float] = (0.05, 0.3)
    debris_radius_mm: tuple[float, float] = (0.15, 0.5)
    debris_grey: tuple[float, float] = (0.05, 0.9)
    """The particle's diffuse reflectance (grey): soot to light dust."""
    sink_radius_mm: tuple[float, float] = (2.5, 5.0)
    sink_depth_mm: tuple[float, float] = (0.02, 0.1)
    """A sink mark: broader and shallower than a dent (steepest tilt 0.4-3.6 deg against a dent's 3-38)."""
    short_shot_fill: tuple[float, float] = (0.3, 0.8)
    """The share of a short stud's height that filled (1.7 mm stud: its top 0.3-1.2 mm low)."""
    warp_sag_mm: tuple[float, float] = (0.1, 0.5)
    """The bow over the body's length (31.8 mm: 0.3-1.6 %, beyond the 0.1-0.3 % a moulded part is usually held
    to), up or down with equal odds; its end faces tilt up to 4 * sag / length (0.7-3.6 deg)."""
    flash_thickness_mm: tuple[float, float] = (0.05, 0.2)
    flash_width_mm: tuple[float, float] = (0.2, 1.0)
    """How far a fin of flash sticks out of the side face (a parting line's flash is rejected from about 0.1 mm)."""
    flash_length_mm: tuple[float, float] = (2.0, 10.0)
    facing_camera: bool = True
    """Place defects on faces that face the camera (they can still be occluded)."""

    def __post_init__(self) -> None:
        kinds = DEFECT_TYPES + NEW_KINDS + MOULDING_KINDS
        bad = [t for t in self.types if t not in kinds]
        if bad or not self.types:
            raise SimError(f"defects.types: unknown {bad or list(self.types)}; choose from {', '.join(kinds)}")
        for f in fields(self):
            v = getattr(self, f.name)
            if isinstance(v, tuple) and f.name != "types":
                if len(v) != 2 or not all(np.isfinite(x) for x in v) or v[0] > v[1] or v[0] < 0:
                    raise SimError(f"defects.{f.name}: need a range (lo, hi) with 0 <= lo <= hi, got {v}")
        for key in ("dent_radius_mm", "scratch_length_mm", "scratch_width_mm", "stain_radius_mm", "chip_size_mm",
                    "scratch_alpha", "stain_alpha", "blister_radius_mm", "debris_radius_mm", "sink_radius_mm",
                    "short_shot_fill", "warp_sag_mm", "flash_thickness_mm", "flash_width_mm",
                    "flash_length_mm"):
            if getattr(self, key)[0] <= 0:
                raise SimError(f"defects.{key}: must be > 0, got {getattr(self, key)}")

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> DefectConfig:
        known = {f.name for f in fields(cls)}
        bad = sorted(set(d) - known)
        if bad:
            raise SimError(f"defects: unknown keys {bad}; known: {', '.join(sorted(known))}")
        return cls(**{k: tuple(v) if isinstance(v, list) else v for k, v in d.items()})

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    def usable_types(self, model: ObjectModel) -> tuple[str, ...]:
        return tuple(t for t in self.types if t not in ("missing_stud", "short_shot") or "studs" in model.features)


@dataclass(frozen=True)
class DefectResult:
    """The defective object (its region moved into part ``defect``), the good object's region for geometric
    defects (None for material-only ones), the parent part's name, sampled material params for the
    ``defect`` material key, and the JSON record of the defect."""

    model: ObjectModel
    good_region: Part | None
    parent: str
    material: dict
    info: dict[str, Any]


def _mm(rng: np.random.Generator, r: tuple[float, float]) -> float:
    return float(rng.uniform(*r)) / 1000.0


def _subpart(part: Part, face_sel: np.ndarray, name: str, material: str, normals: np.ndarray | None = None) -> Part:
    """Faces ``face_sel`` (bool) of ``part`` as a compact new part (normals taken from ``normals`` or part)."""
    faces = part.faces[face_sel]
    used, inv = np.unique(faces, return_inverse=True)
    n = part.normals if normals is None else normals
    tags = None if part.tags is None else part.tags[face_sel]
    return Part(name, part.vertices[used], inv.reshape(-1, 3).astype(np.int32), n[used], material, tags)


def _pick_face(rng: np.random.Generator, part: Part, cam_obj: np.ndarray, facing: bool,
               mask: np.ndarray | None = None) -> tuple[int, np.ndarray, np.ndarray]:
    """A random face (area-weighted) and a uniform point on it; faces facing ``cam_obj`` if asked."""
    v = part.vertices.astype(np.float64)
    tri = v[part.faces]
    fn = face_normals(v, part.faces)
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    ok = area > 0 if mask is None else (area > 0) & mask
    if facing:
        towards = np.einsum("ij,ij->i", fn, cam_obj - tri.mean(1)) > 0
        if np.any(ok & towards):
            ok &= towards
    if not np.any(ok):
        raise SimError(f"part {part.name!r} has no face to place a defect on")
    w = np.where(ok, area, 0.0)
    f = int(rng.choice(len(w), p=w / w.sum()))
    a, b = rng.random(2)
    if a + b > 1:
        a, b = 1 - a, 1 - b
    point = tri[f, 0] + a * (tri[f, 1] - tri[f, 0]) + b * (tri[f, 2] - tri[f, 0])
    return f, point, fn[f]


def _segment_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ab = b - a
    t = np.clip(((p - a) @ ab) / max(float(ab @ ab), 1e-30), 0, 1)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=1)


def _split_body(model: ObjectModel, body: Part, new_vertices: np.ndarray, region: np.ndarray, material_key: str
                ) -> tuple[ObjectModel, Part]:
    """Body with moved vertices split into the rest and the ``defect`` part (normals from the whole body)."""
    if not region.any():
        raise SimError(f"defect region on part {body.name!r} holds no faces (mesh too coarse for the defect size)")
    normals = vertex_normals(new_vertices, body.faces)
    moved = Part(body.name, new_vertices.astype(np.float32), body.faces, normals, body.material, body.tags)
    rest = _subpart(moved, ~region, body.name, body.material)
    defect = _subpart(moved, region, DEFECT_PART, material_key)
    parts = [rest if p.name == body.name else p for p in model.parts] + [defect]
    return model.with_parts(parts), _subpart(body, region, DEFECT_PART, material_key)


def apply_defect(model: ObjectModel, kind: str, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray,
                 materials: dict[str, dict]) -> DefectResult:
    """Put one defect of ``kind`` on ``model``'s body. ``cam_obj``: camera position in object coordinates;
    ``materials``: the sampled material params (``sim.scene.sample_material``) of the good object. Each type is
    one function of ``_DEFECTS``; they draw from ``rng`` in a fixed order, so a seed gives the same defect."""
    if kind not in cfg.usable_types(model):
        raise SimError(f"defect type {kind!r} is not possible on object {model.name!r} "
                       f"(possible: {', '.join(cfg.usable_types(model))})")
    if kind not in _DEFECTS:
        raise SimError(f"unknown defect type {kind!r}")
    return _DEFECTS[kind](_Body.of(model, kind, materials), rng, cfg, cam_obj)


@dataclass(frozen=True)
class _Body:
    """The body part a defect goes on and what the defect types read of it: vertices (float64), face centroids
    and normals, the parent material's sampled params, and the record's first entries (type, part)."""

    model: ObjectModel
    part: Part
    v: np.ndarray
    centroids: np.ndarray
    fn: np.ndarray
    material: dict
    info: dict[str, Any]

    @classmethod
    def of(cls, model: ObjectModel, kind: str, materials: dict[str, dict]) -> _Body:
        body = model.part(model.body)
        v = body.vertices.astype(np.float64)
        return cls(model, body, v, v[body.faces].mean(1), face_normals(v, body.faces), dict(materials[body.material]),
                   {"type": kind, "part": body.name})


def _missing_stud(b: _Body, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray) -> DefectResult:
    """One stud removed (preferably one the camera sees from above), with its footprint on the body's top."""
    model, body = b.model, b.part
    studs = model.part("studs")
    k, _, centre, _ = _top_stud(model, rng, cfg, cam_obj)
    sv = studs.vertices[np.unique(studs.faces[studs.tags == k])]
    radius = float(np.max(np.linalg.norm(sv[:, :2] - centre[:2], axis=1)))
    body_top = float(b.v[:, 2].max())
    region = (np.linalg.norm(b.centroids[:, :2] - centre[:2], axis=1) < radius) & (b.fn[:, 2] > 0.9) & (
        b.centroids[:, 2] > body_top - 1e-6)
    kept = _subpart(studs, studs.tags != k, studs.name, studs.material)
    removed = _subpart(studs, studs.tags == k, DEFECT_PART, body.material)
    footprint = _subpart(body, region, DEFECT_PART, body.material)
    rest = _subpart(body, ~region, body.name, body.material)
    parts = [rest if p.name == body.name else kept if p.name == studs.name else p for p in model.parts]
    good = Part(DEFECT_PART, np.concatenate([removed.vertices, footprint.vertices]),
                np.concatenate([removed.faces, footprint.faces + len(removed.vertices)]),
                np.concatenate([removed.normals, footprint.normals]), body.material)
    info = {**b.info, "stud": k, "centre_m": centre.tolist(), "radius_mm": radius * 1000}
    return DefectResult(model.with_parts([*parts, footprint]), good, body.name, b.material, info)


def _top_stud(model: ObjectModel, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray
              ) -> tuple[int, np.ndarray, np.ndarray, float]:
    """A stud the camera sees from above (any when none is): (its number, its faces' selection in ``studs``, its
    centre on the body's top (m), the studs' top height (m))."""
    studs = model.part("studs")
    top = studs.vertices[:, 2].max()  # float32, as the centres' other coordinates (the pinned draws)
    centres = []
    for k in range(int(studs.tags.max()) + 1):
        sv = studs.vertices[np.unique(studs.faces[studs.tags == k])]
        centres.append([sv[:, 0].mean(), sv[:, 1].mean(), top])
    centres = np.asarray(centres)
    ok = (cam_obj - centres)[:, 2] > 0 if cfg.facing_camera else np.ones(len(centres), bool)
    k = int(rng.choice(np.flatnonzero(ok) if ok.any() else np.arange(len(centres))))
    return k, studs.tags == k, centres[k], float(top)


def _short_shot(b: _Body, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray) -> DefectResult:
    """One stud filled short: its height scaled to the drawn share (the body's top stays), the full stud as the good
    region."""
    model = b.model
    studs = model.part("studs")
    k, sel, centre, top = _top_stud(model, rng, cfg, cam_obj)
    fill = float(rng.uniform(*cfg.short_shot_fill))
    base = float(b.v[:, 2].max())
    stud = _subpart(studs, sel, DEFECT_PART, b.part.material)
    v = stud.vertices.astype(np.float64)
    v[:, 2] = base + (v[:, 2] - base) * fill
    # a height scaled along z keeps a cylinder's normals (its side's have no z, its top's only z)
    short = Part(DEFECT_PART, v.astype(np.float32), stud.faces, stud.normals, b.part.material)
    kept = _subpart(studs, ~sel, studs.name, studs.material)
    parts = [kept if p.name == studs.name else p for p in model.parts]
    info = {**b.info, "stud": k, "centre_m": centre.tolist(), "fill": fill,
            "short_mm": (top - base) * (1 - fill) * 1000}
    return DefectResult(model.with_parts([*parts, short]), stud, b.part.name, b.material, info)


def _warp(b: _Body, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray) -> DefectResult:
    """The whole part bowed along x: every vertex of every part raised by ``sag (1 - u^2)`` at u = 2 x / the body's
    length (carried on straight past the body's ends: the plug tilts with its end), less the bow's lowest point so
    the part rests on the belt. The bowed body is the defect part, the flat one its good region."""
    model = b.model
    x0, x1 = float(b.v[:, 0].min()), float(b.v[:, 0].max())
    sag = _mm(rng, cfg.warp_sag_mm) * (1.0 if rng.random() < 0.5 else -1.0)

    def bowed(p: Part) -> tuple[np.ndarray, np.ndarray]:
        """The part's vertices raised by the bow and its normals turned with it (z += f(x) maps a normal n to
        (n_x - f'(x) n_z, n_y, n_z), normalised)."""
        v, n = p.vertices.astype(np.float64), p.normals.astype(np.float64)
        u = (2 * v[:, 0] - (x0 + x1)) / (x1 - x0)
        inside = np.abs(u) <= 1
        dz = sag * np.where(inside, 1 - u**2, -2 * (np.abs(u) - 1)) - min(sag, 0.0)
        slope = sag * np.where(inside, -2 * u, -2 * np.sign(u)) * 2 / (x1 - x0)
        n = np.c_[n[:, 0] - slope * n[:, 2], n[:, 1:]]
        return np.c_[v[:, :2], v[:, 2] + dz], n / np.linalg.norm(n, axis=1, keepdims=True)

    parts = []
    for p in model.parts:
        v, n = bowed(p)
        name = DEFECT_PART if p.name == b.part.name else p.name
        parts.append(Part(name, v.astype(np.float32), p.faces, n.astype(np.float32), p.material, p.tags))
    good = _subpart(b.part, np.ones(len(b.part.faces), bool), DEFECT_PART, b.part.material)
    info = {**b.info, "sag_mm": sag * 1000, "length_mm": (x1 - x0) * 1000}
    return DefectResult(model.with_parts(parts), good, b.part.name, b.material, info)


def _chip(b: _Body, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray) -> DefectResult:
    """A sharp edge or corner of the body cut off by a plane (preferably an edge facing the camera)."""
    v, body = b.v, b.part
    key = np.round(v / 1e-7).astype(np.int64)
    _, group = np.unique(key, axis=0, return_inverse=True)
    group = group.ravel()
    nrm = body.normals.astype(np.float64)
    # a vertex is on a sharp edge when vertices at its position carry different normals
    gsum = np.zeros((group.max() + 1, 3))
    np.add.at(gsum, group, nrm)
    gcount = np.bincount(group)
    spread = np.linalg.norm(gsum[group] / gcount[group, None], axis=1)
    edge = spread < 0.95
    dirs = gsum[group] / np.maximum(np.linalg.norm(gsum[group], axis=1, keepdims=True), 1e-12)
    if cfg.facing_camera:
        facing = np.einsum("ij,ij->i", dirs, cam_obj - v) > 0
        if np.any(edge & facing):
            edge &= facing
    # not on the resting bottom edges only: any sharp edge of the body
    cand = np.flatnonzero(edge)
    if not len(cand):
        raise SimError(f"object {b.model.name!r}: body has no sharp edge to chip")
    i = int(rng.choice(cand))
    c, n = v[i], dirs[i]
    size = _mm(rng, cfg.chip_size_mm)
    reach = 3.0 * size
    h = (v - c) @ n + size  # > 0: beyond the cutting plane
    r = np.linalg.norm(v - c, axis=1)
    w = np.clip((reach - r) / (0.4 * reach), 0, 1)
    shift = w * np.maximum(h, 0)
    new_v = v - shift[:, None] * n
    region = (shift[body.faces] > 1e-9).any(1)
    if not region.any():
        raise SimError("chip removed nothing (chip_size_mm too small for the mesh)")
    new_model, good = _split_body(b.model, body, new_v, region, body.material)
    info = {**b.info, "centre_m": c.tolist(), "normal": n.tolist(), "size_mm": size * 1000}
    return DefectResult(new_model, good, body.name, b.material, info)


def _bump(b: _Body, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray, radius_mm: tuple[float, float],
          size_mm: tuple[float, float], sign: float, size_key: str) -> DefectResult:
    """A smooth cosine-profile bump of a drawn radius and size (recorded as ``size_key``, mm) pushed along the face
    normal times ``sign``: -1 in (a dent), +1 out (a blister)."""
    v, body = b.v, b.part
    _, c, n = _pick_face(rng, b.part, cam_obj, cfg.facing_camera)
    radius, size = _mm(rng, radius_mm), _mm(rng, size_mm)
    r = np.linalg.norm(v - c, axis=1)
    w = np.where(r < radius, 0.5 * (1 + np.cos(np.pi * np.minimum(r / radius, 1))), 0.0)
    new_v = v + (sign * size * w)[:, None] * n
    region = (r[body.faces] < radius).any(1)
    new_model, good = _split_body(b.model, body, new_v, region, body.material)
    info = {**b.info, "centre_m": c.tolist(), "normal": n.tolist(), "radius_mm": radius * 1000, size_key: size * 1000}
    return DefectResult(new_model, good, body.name, b.material, info)


def _dent(b: _Body, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray) -> DefectResult:
    """A smooth cosine-profile depression pushed in along the face normal."""
    return _bump(b, rng, cfg, cam_obj, cfg.dent_radius_mm, cfg.dent_depth_mm, -1.0, "depth_mm")


def _sink(b: _Body, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray) -> DefectResult:
    """A sink mark: a dent's cosine profile, broad and shallow."""
    return _bump(b, rng, cfg, cam_obj, cfg.sink_radius_mm, cfg.sink_depth_mm, -1.0, "depth_mm")


def _blister(b: _Body, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray) -> DefectResult:
    """A smooth cosine-profile bump pushed out along the face normal (a dent's mirror image)."""
    return _bump(b, rng, cfg, cam_obj, cfg.blister_radius_mm, cfg.blister_height_mm, 1.0, "height_mm")


def _debris(b: _Body, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray) -> DefectResult:
    """A matte sphere resting on a face, sunk by a fifth of its radius (its contact), of ``diffuse`` grey."""
    import trimesh

    _, c, n = _pick_face(rng, b.part, cam_obj, cfg.facing_camera)
    radius = _mm(rng, cfg.debris_radius_mm)
    grey = float(rng.uniform(*cfg.debris_grey))
    ball = trimesh.creation.icosphere(subdivisions=3, radius=1.0)
    unit = np.asarray(ball.vertices, dtype=np.float64)
    v = c + 0.8 * radius * n + radius * unit
    particle = Part(DEFECT_PART, v.astype(np.float32), np.asarray(ball.faces, dtype=np.int32),
                    unit.astype(np.float32), DEFECT_PART)
    info = {**b.info, "centre_m": c.tolist(), "normal": n.tolist(), "radius_mm": radius * 1000, "grey": grey}
    material = {"type": "diffuse", "colour": [grey] * 3}
    return DefectResult(b.model.with_parts([*b.model.parts, particle]), None, b.part.name, material, info)


def _scratch(b: _Body, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray) -> DefectResult:
    """A line of rougher material on one face, optionally a shallow groove (which may reach over an edge)."""
    v, body = b.v, b.part
    f, c, n = _pick_face(rng, b.part, cam_obj, cfg.facing_camera)
    same_face = b.fn @ n > 0.9
    length, width = _mm(rng, cfg.scratch_length_mm), _mm(rng, cfg.scratch_width_mm)
    depth = _mm(rng, cfg.scratch_depth_mm)
    t = np.cross(n, rng.normal(size=3))
    t /= np.linalg.norm(t)
    a, e = c - 0.5 * length * t, c + 0.5 * length * t
    edge_len = float(np.median(np.linalg.norm(v[body.faces[:, 1]] - v[body.faces[:, 0]], axis=1)))
    half = max(0.5 * width, 0.6 * edge_len)  # at least one row of faces
    region = same_face & (_segment_distance(b.centroids, a, e) < half)
    if not region.any():
        region[f] = True
    d = _segment_distance(v, a, e)
    w = np.clip(1 - (d / half) ** 2, 0, 1) if depth > 0 else np.zeros(len(v))
    region |= (w[body.faces] > 0).any(1)  # a groove that reaches over an edge moves faces there too
    new_v = v - (depth * w)[:, None] * n
    mat = dict(b.material, alpha=float(rng.uniform(*cfg.scratch_alpha)))
    new_model, good = _split_body(b.model, body, new_v, region, DEFECT_PART)
    info = {**b.info, "start_m": a.tolist(), "end_m": e.tolist(), "normal": n.tolist(), "length_mm": length * 1000,
            "width_mm": width * 1000, "depth_mm": depth * 1000, "alpha": mat["alpha"]}
    return DefectResult(new_model, good if depth > 0 else None, body.name, mat, info)


def _stain(b: _Body, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray) -> DefectResult:
    """A disc of darker, rougher material (contamination) on one face; the geometry is unchanged."""
    f, c, n = _pick_face(rng, b.part, cam_obj, cfg.facing_camera)
    same_face = b.fn @ n > 0.9
    radius = _mm(rng, cfg.stain_radius_mm)
    region = same_face & (np.linalg.norm(b.centroids - c, axis=1) < radius)
    if not region.any():
        region[f] = True
    k = float(rng.uniform(*cfg.stain_darken))
    mat = dict(b.material, colour=[k * x for x in b.material.get("colour", [0.5, 0.5, 0.5])],
               alpha=float(rng.uniform(*cfg.stain_alpha)))
    new_model, _ = _split_body(b.model, b.part, b.v, region, DEFECT_PART)
    info = {**b.info, "centre_m": c.tolist(), "normal": n.tolist(), "radius_mm": radius * 1000, "darken": k,
            "alpha": mat["alpha"]}
    return DefectResult(new_model, None, b.part.name, mat, info)


def _flash(b: _Body, rng: np.random.Generator, cfg: DefectConfig, cam_obj: np.ndarray) -> DefectResult:
    """A fin of the body's plastic along one of its four side faces' top or bottom edge (preferably a face the camera
    sees), sticking straight out of it: a box ``width`` beyond the face (and 0.5 mm into the body, so a broken edge
    leaves no gap), ``thickness`` high, its flat side 0.01 mm inside the top or bottom plane (no two faces at one
    place), ``length`` along the edge (at most the edge's), placed uniformly along it."""
    lo, hi = b.v.min(0), b.v.max(0)
    sides = [(axis, sign) for axis in (0, 1) for sign in (-1.0, 1.0)]
    if cfg.facing_camera:
        seen = [(a, s) for a, s in sides if s * (cam_obj[a] - (hi[a] if s > 0 else lo[a])) > 0]
        sides = seen or sides
    axis, sign = sides[int(rng.integers(len(sides)))]
    top = bool(rng.random() < 0.5)
    thickness, width = _mm(rng, cfg.flash_thickness_mm), _mm(rng, cfg.flash_width_mm)
    along = 1 - axis
    length = min(_mm(rng, cfg.flash_length_mm), float(hi[along] - lo[along]))
    start = float(rng.uniform(lo[along], hi[along] - length))
    face = hi[axis] if sign > 0 else lo[axis]
    inset, gap = 5e-4, 1e-5
    box_lo, box_hi = np.empty(3), np.empty(3)
    box_lo[along], box_hi[along] = start, start + length
    box_lo[axis], box_hi[axis] = sorted((face - sign * inset, face + sign * width))
    box_lo[2] = hi[2] - gap - thickness if top else lo[2] + gap
    box_hi[2] = box_lo[2] + thickness
    v, f = box_mesh(box_lo, box_hi, 5e-4)
    fin = Part(DEFECT_PART, v.astype(np.float32), f.astype(np.int32), vertex_normals(v, f).astype(np.float32),
               DEFECT_PART)
    normal = np.zeros(3)
    normal[axis] = sign
    centre = (box_lo + box_hi) / 2
    centre[axis] = face
    info = {**b.info, "centre_m": centre.tolist(), "normal": normal.tolist(), "edge": "top" if top else "bottom",
            "thickness_mm": thickness * 1000, "width_mm": width * 1000, "length_mm": length * 1000}
    return DefectResult(b.model.with_parts([*b.model.parts, fin]), None, b.part.name, b.material, info)


_DEFECTS: dict[str, Callable[[_Body, np.random.Generator, DefectConfig, np.ndarray], DefectResult]] = {
    "dent": _dent, "scratch": _scratch, "stain": _stain, "chip": _chip, "missing_stud": _missing_stud,
    "blister": _blister, "debris": _debris, "sink": _sink, "short_shot": _short_shot, "warp": _warp,
    "flash": _flash}
"""Defect type -> the function that puts it on a body (one per name of ``DEFECT_TYPES``, ``NEW_KINDS`` and
``MOULDING_KINDS``)."""
