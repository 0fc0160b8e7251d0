"""Object meshes with per-part materials: the paper's reference object generated in code, and user PLY/OBJ files.

Units: metres. Object frame: z up, the object's bottom at z = 0 in its design pose (resting poses come from
``stable_poses``). Triangles wind counter-clockwise seen from outside, so face normals point outward.

Flat faces are tessellated into a fine grid (``cell_mm``) with their own vertices (not shared across sharp
edges): defects (``sim.defects``) select and deform faces of a region, and shading normals stay flat on faces
and smooth on curved surfaces.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from .errors import SimError

# A 2x4 construction brick (outer dimensions of the common toy brick) with a USB-A plug on one short end.
BRICK_SIZE_MM = (31.8, 15.8, 9.6)
STUD_RADIUS_MM = 2.4
STUD_HEIGHT_MM = 1.7
STUD_PITCH_MM = 8.0
PLUG_SIZE_MM = (12.0, 12.0, 4.5)  # length (x, out of the brick), width (y), height (z)
SHARP_EDGE_DEG = 30.0
MAX_EDGE_M = 1e-3
"""User meshes are subdivided to edges of at most 1 mm so that defects have faces to move (at most 8 halvings)."""


@dataclass(frozen=True)
class Part:
    """One mesh with one material.

    vertices : (N, 3) float32, metres.  faces : (M, 3) int32 vertex indices.  normals : (N, 3) float32 unit
    shading normals.  material : key into ``ObjectModel.materials``.  tags : optional (M,) int32 per-face
    label (for the studs: which stud; -1 where unused).
    """

    name: str
    vertices: np.ndarray
    faces: np.ndarray
    normals: np.ndarray
    material: str
    tags: np.ndarray | None = None


@dataclass(frozen=True)
class ObjectModel:
    """An object: parts and the material spec of each material key (``sim.scene.MaterialSpec`` dicts).

    ``features`` lists what defects need beyond a surface ("studs"); ``body`` names the part defects go on.
    ``rests_as``: an object whose resting poses this one takes (``stable_poses``), None for its own.
    """

    name: str
    parts: tuple[Part, ...]
    materials: dict[str, dict]
    body: str
    features: tuple[str, ...] = field(default=())
    rests_as: ObjectModel | None = None

    def part(self, name: str) -> Part:
        for p in self.parts:
            if p.name == name:
                return p
        raise SimError(f"object {self.name!r} has no part {name!r}; parts: {', '.join(p.name for p in self.parts)}")

    def with_parts(self, parts: list[Part] | tuple[Part, ...]) -> ObjectModel:
        return replace(self, parts=tuple(parts))


def face_normals(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Unit face normals (M, 3) (zero for degenerate faces), counter-clockwise winding."""
    v = vertices.astype(np.float64)
    n = np.cross(v[faces[:, 1]] - v[faces[:, 0]], v[faces[:, 2]] - v[faces[:, 0]])
    length = np.linalg.norm(n, axis=1, keepdims=True)
    return np.divide(n, length, out=np.zeros_like(n), where=length > 0)


def vertex_normals(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Area-weighted unit vertex normals (N, 3) float32; vertices not shared across sharp edges stay flat."""
    v = vertices.astype(np.float64)
    n = np.cross(v[faces[:, 1]] - v[faces[:, 0]], v[faces[:, 2]] - v[faces[:, 0]])  # length = 2 * area
    acc = np.zeros_like(v)
    for k in range(3):
        np.add.at(acc, faces[:, k], n)
    length = np.linalg.norm(acc, axis=1, keepdims=True)
    return np.divide(acc, length, out=np.zeros_like(acc), where=length > 0).astype(np.float32)


def _grid(origin: np.ndarray, u: np.ndarray, v: np.ndarray, cell: float) -> tuple[np.ndarray, np.ndarray]:
    """A rectangle origin + s*u + t*v (s, t in [0, 1]) as a triangle grid of cells <= ``cell``; normal u x v."""
    nu = max(1, int(np.ceil(np.linalg.norm(u) / cell)))
    nv = max(1, int(np.ceil(np.linalg.norm(v) / cell)))
    s, t = np.meshgrid(np.linspace(0, 1, nu + 1), np.linspace(0, 1, nv + 1), indexing="ij")
    verts = origin + s.reshape(-1, 1) * u + t.reshape(-1, 1) * v
    idx = np.arange((nu + 1) * (nv + 1)).reshape(nu + 1, nv + 1)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    faces = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    return verts, faces


def _merge(pieces: list[tuple[np.ndarray, np.ndarray]]) -> tuple[np.ndarray, np.ndarray]:
    verts, faces, base = [], [], 0
    for v, f in pieces:
        verts.append(v)
        faces.append(f + base)
        base += len(v)
    return np.concatenate(verts), np.concatenate(faces)


def box_mesh(lo: np.ndarray, hi: np.ndarray, cell: float, skip: tuple[str, ...] = ()) -> tuple[np.ndarray, np.ndarray]:
    """Axis-aligned box [lo, hi] as six gridded faces (outward normals); ``skip`` names faces left out
    ("-x", "+x", "-y", "+y", "-z", "+z")."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    d = hi - lo
    ex, ey, ez = np.diag(d)
    sides = {
        "-z": (lo, ey, ex), "+z": (lo + ez, ex, ey),
        "-y": (lo, ex, ez), "+y": (lo + ey, ez, ex),
        "-x": (lo, ez, ey), "+x": (lo + ex, ey, ez),
    }
    return _merge([_grid(np.asarray(o), u, v, cell) for name, (o, u, v) in sides.items() if name not in skip])


def chamfered_box_mesh(lo: np.ndarray, hi: np.ndarray, chamfer: float, cell: float) -> tuple[np.ndarray, np.ndarray]:
    """Axis-aligned box [lo, hi] whose 12 edges are cut at 45 degrees, ``chamfer`` (metres) back along each face:
    six faces shrunk by the chamfer, twelve strips and eight corner triangles, each with its own vertices
    (outward normals; a strip meets its faces along edges subdivided alike)."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    ctr, half = (lo + hi) / 2, (hi - lo) / 2
    if not 0 < chamfer < half.min():
        raise SimError(f"edge chamfer {chamfer * 1000:g} mm must be > 0 and less than half the box's smallest side")
    inner = half - chamfer
    pieces: list[tuple[np.ndarray, np.ndarray]] = []

    def rectangle(p0: np.ndarray, p1: np.ndarray, p3: np.ndarray) -> None:
        u, v = p1 - p0, p3 - p0
        if np.dot(np.cross(u, v), p0 + (u + v) / 2 - ctr) < 0:
            u, v = v, u
        pieces.append(_grid(p0, u, v, cell))

    for i in range(3):  # faces
        j, k = (i + 1) % 3, (i + 2) % 3
        for si in (-1, 1):
            p0 = ctr.copy()
            p0[i] += si * half[i]
            p0[j] -= inner[j]
            p0[k] -= inner[k]
            p1, p3 = p0.copy(), p0.copy()
            p1[j] += 2 * inner[j]
            p3[k] += 2 * inner[k]
            rectangle(p0, p1, p3)
    for k in range(3):  # strips along axis k, between the faces normal to i and j
        i, j = (k + 1) % 3, (k + 2) % 3
        for si in (-1, 1):
            for sj in (-1, 1):
                on_i, on_j = ctr.copy(), ctr.copy()
                on_i[i] += si * half[i]
                on_i[j] += sj * inner[j]
                on_j[i] += si * inner[i]
                on_j[j] += sj * half[j]
                on_i[k] = on_j[k] = ctr[k] - inner[k]
                far = on_i.copy()
                far[k] = ctr[k] + inner[k]
                rectangle(on_i, on_j, far)
    for signs in np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1], indexing="ij")).reshape(3, -1).T:  # corners
        tri = np.array([ctr + signs * np.where(np.arange(3) == a, half, inner) for a in range(3)])
        if np.dot(np.cross(tri[1] - tri[0], tri[2] - tri[0]), tri.mean(0) - ctr) < 0:
            tri = tri[[0, 2, 1]]
        pieces.append((tri, np.array([[0, 1, 2]])))
    return _merge(pieces)


EDGE_SHAPES = ("chamfer", "round")
"""How the brick's body edges are broken (``usb_brick``'s ``edge_shape``): cut at 45 degrees, or rounded."""
ROUND_SEGMENTS = 8
"""Segments of a rounded edge's quarter circle (``rounded_box_mesh``): 11 degrees each, shaded smooth."""


def rounded_box_mesh(lo: np.ndarray, hi: np.ndarray, radius: float, cell: float, segments: int = ROUND_SEGMENTS
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Axis-aligned box [lo, hi] whose 12 edges are rounded to ``radius`` (metres; a fillet, as a moulded part's):
    six faces shrunk by the radius, twelve quarter cylinders and eight sphere octants, each with its own vertices.
    Returns vertices, faces (outward normals) and unit shading normals: flat on the faces, radial on the rounds, so
    a round shades smooth and meets its faces without a crease (a chip, which cuts a crease, finds none)."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    ctr, half = (lo + hi) / 2, (hi - lo) / 2
    if not 0 < radius < half.min():
        raise SimError(f"edge radius {radius * 1000:g} mm must be > 0 and less than half the box's smallest side")
    inner, eye, n = half - radius, np.eye(3), segments
    pieces: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []

    def add(v: np.ndarray, f: np.ndarray, nrm: np.ndarray) -> None:  # wound to agree with the shading normals
        geo = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
        pieces.append((v, f[:, [0, 2, 1]] if np.sum(geo * nrm[f].sum(1)) < 0 else f, nrm))

    for i in range(3):  # faces
        j, k = (i + 1) % 3, (i + 2) % 3
        for si in (-1, 1):
            p0 = ctr + si * half[i] * eye[i] - inner[j] * eye[j] - inner[k] * eye[k]
            v, f = _grid(p0, 2 * inner[j] * eye[j], 2 * inner[k] * eye[k], cell)
            add(v, f, np.tile(si * eye[i], (len(v), 1)))
    arc = np.arange(n + 1)[:, None]
    for k in range(3):  # quarter cylinders along axis k, between the faces normal to i and j
        i, j = (k + 1) % 3, (k + 2) % 3
        nk = max(1, int(np.ceil(2 * inner[k] / cell)))  # as the faces' grid along k: the rows meet
        t = np.linspace(-inner[k], inner[k], nk + 1)
        for si in (-1, 1):
            for sj in (-1, 1):
                d = (n - arc) * si * eye[i] + arc * sj * eye[j]
                d /= np.linalg.norm(d, axis=1, keepdims=True)
                axis = ctr + si * inner[i] * eye[i] + sj * inner[j] * eye[j] + t[:, None] * eye[k]
                v = (axis[:, None, :] + radius * d[None]).reshape(-1, 3)
                idx = np.arange(len(v)).reshape(nk + 1, n + 1)
                a, b, c, e = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
                add(v, np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, e], 1)]), np.tile(d, (nk + 1, 1)))
    ab = [(a, b) for a in range(n + 1) for b in range(n + 1 - a)]  # octants: a triangle of n rows on the sphere
    number = {key: m for m, key in enumerate(ab)}
    tris = [(number[a, b], number[a + 1, b], number[a, b + 1]) for a, b in ab if a + b < n]
    tris += [(number[a + 1, b], number[a + 1, b + 1], number[a, b + 1]) for a, b in ab if a + b < n - 1]
    for signs in np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1], indexing="ij")).reshape(3, -1).T:
        d = np.array([(a, b, n - a - b) for a, b in ab], float) * signs
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        add(ctr + signs * inner + radius * d, np.array(tris), d)
    verts, faces = _merge([(v, f) for v, f, _ in pieces])
    return verts, faces, np.concatenate([nrm for _, _, nrm in pieces])


def cylinder_mesh(center: np.ndarray, radius: float, height: float, segments: int, cell: float
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Vertical cylinder (side + top cap, open bottom) standing on ``center``; returns vertices, faces and
    smooth shading normals (radial on the side, +z on the cap)."""
    ang = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    ring = np.stack([np.cos(ang), np.sin(ang), np.zeros_like(ang)], 1)
    rows = max(1, int(np.ceil(height / cell)))
    zs = np.linspace(0, height, rows + 1)
    side_v = np.concatenate([center + radius * ring + [0, 0, z] for z in zs])
    side_n = np.tile(ring, (rows + 1, 1))
    idx = np.arange((rows + 1) * segments).reshape(rows + 1, segments)
    a, b = idx[:-1], np.roll(idx[:-1], -1, axis=1)
    c, d = np.roll(idx[1:], -1, axis=1), idx[1:]
    side_f = np.concatenate([np.stack([a.ravel(), b.ravel(), c.ravel()], 1),
                             np.stack([a.ravel(), c.ravel(), d.ravel()], 1)])
    # cap: concentric rings so that the cap is also finely tessellated
    n_rings = max(1, int(np.ceil(radius / cell)))
    cap_v = [center + np.array([0, 0, height])]
    for k in range(1, n_rings + 1):
        cap_v.append(center + (radius * k / n_rings) * ring + np.array([0, 0, height]))
    cap_v = np.concatenate([np.atleast_2d(x) for x in cap_v])
    cap_f = [np.stack([np.zeros(segments, int), 1 + np.arange(segments), 1 + np.roll(np.arange(segments), -1)], 1)]
    for k in range(1, n_rings):
        inner = 1 + (k - 1) * segments + np.arange(segments)
        outer = inner + segments
        cap_f.append(np.stack([inner, outer, np.roll(outer, -1)], 1))
        cap_f.append(np.stack([inner, np.roll(outer, -1), np.roll(inner, -1)], 1))
    cap_f = np.concatenate(cap_f)
    cap_n = np.tile([0.0, 0.0, 1.0], (len(cap_v), 1))
    verts = np.concatenate([side_v, cap_v])
    faces = np.concatenate([side_f, cap_f + len(side_v)])
    return verts, faces, np.concatenate([side_n, cap_n])


def _part(name: str, verts: np.ndarray, faces: np.ndarray, material: str, normals: np.ndarray | None = None,
          tags: np.ndarray | None = None) -> Part:
    v = np.ascontiguousarray(verts, dtype=np.float32)
    f = np.ascontiguousarray(faces, dtype=np.int32)
    n = vertex_normals(v, f) if normals is None else np.ascontiguousarray(normals, dtype=np.float32)
    return Part(name, v, f, n, material, None if tags is None else np.ascontiguousarray(tags, dtype=np.int32))


BRICK_MATERIALS: dict[str, dict] = {
    "plastic": {"type": "pplastic", "finish": "smooth"},
    "metal": {"type": "roughconductor", "material": "Al", "finish": "rough"},
}


@functools.lru_cache(maxsize=4)
def usb_brick(cell_mm: float = 0.5, edge_mm: float = 0.0, edge_shape: str = "chamfer") -> ObjectModel:
    """The paper's reference object: a USB stick shaped as a 2x4 construction brick.

    Parts: ``body`` (the brick, polarized plastic ``pplastic``), ``studs`` (eight studs on top, same
    plastic; per-face ``tags`` = stud number 0..7), ``plug`` (USB-A plug shell, ``roughconductor``),
    sticking out of the +x end, centred in y and z. Origin at the centre of the brick's bottom. ``edge_mm``: the
    body's edges cut at 45 degrees that far back along each face (``edge_shape`` "chamfer": ``chamfered_box_mesh``)
    or rounded to that radius ("round": ``rounded_box_mesh``); 0: sharp, as designed.
    """
    cell = cell_mm / 1000.0
    lx, ly, lz = (s / 1000.0 for s in BRICK_SIZE_MM)
    lo, hi = np.array([-lx / 2, -ly / 2, 0]), np.array([lx / 2, ly / 2, lz])
    if edge_shape not in EDGE_SHAPES:
        raise SimError(f"edge shape {edge_shape!r}: use one of {', '.join(EDGE_SHAPES)}")
    body_n = None
    if not edge_mm:
        body_v, body_f = box_mesh(lo, hi, cell)
    elif edge_shape == "round":
        body_v, body_f, body_n = rounded_box_mesh(lo, hi, edge_mm / 1000, cell)
    else:
        body_v, body_f = chamfered_box_mesh(lo, hi, edge_mm / 1000, cell)
    r, h, pitch = STUD_RADIUS_MM / 1000, STUD_HEIGHT_MM / 1000, STUD_PITCH_MM / 1000
    studs, tags = [], []
    for k, (i, j) in enumerate((i, j) for i in range(4) for j in range(2)):
        c = np.array([(i - 1.5) * pitch, (j - 0.5) * pitch, lz])
        v, f, n = cylinder_mesh(c, r, h, 32, cell * 2)
        studs.append((v, f, n))
        tags.append(np.full(len(f), k))
    sv, sf = _merge([(v, f) for v, f, _ in studs])
    sn = np.concatenate([n for _, _, n in studs])
    px, py, pz = (s / 1000.0 for s in PLUG_SIZE_MM)
    plug_lo = np.array([lx / 2, -py / 2, lz / 2 - pz / 2])
    plug_v, plug_f = box_mesh(plug_lo, plug_lo + np.array([px, py, pz]), cell * 2, skip=("-x",))
    parts = (
        _part("body", body_v, body_f, "plastic", body_n),
        _part("studs", sv, sf, "plastic", sn, np.concatenate(tags)),
        _part("plug", plug_v, plug_f, "metal"),
    )
    # a round's hull has its resting poses turned about z as trimesh pleases (the plug to the left); the brick rests
    # on the same flat faces with its edges broken, so it takes the sharp brick's poses
    rests_as = usb_brick(cell_mm) if edge_mm and edge_shape == "round" else None
    return ObjectModel("usb_brick", parts, dict(BRICK_MATERIALS), body="body", features=("studs",), rests_as=rests_as)


def material_spec(material: str | dict) -> dict:
    """A material as given (a Mitsuba BSDF type such as ``"pplastic"``, or a spec dict) -> a spec dict of its own."""
    return {"type": material} if isinstance(material, str) else dict(material)


def load_mesh(path: str | Path, materials: dict[str, str | dict], scale: float = 1.0, body: str | None = None
              ) -> ObjectModel:
    """A user PLY/OBJ as an ``ObjectModel``: each named geometry in the file (OBJ objects/groups; a PLY is one
    part named after the file) is a part. ``materials`` maps part name -> material (a Mitsuba BSDF type such as
    ``"pplastic"`` or a dict ``{"type": ..., "finish": "rough"|"smooth", ...}``); key ``"*"`` is the default.
    ``scale`` converts file units to metres. Raises SimError naming the file or part."""
    import trimesh

    path = Path(path)
    if not path.is_file():
        raise SimError(f"mesh file {path} does not exist")
    try:
        scene = trimesh.load(path, force="scene", process=False)
    except Exception as exc:
        raise SimError(f"mesh file {path}: cannot be read ({exc})") from None
    geoms = {name: g for name, g in scene.geometry.items() if isinstance(g, trimesh.Trimesh) and len(g.faces)}
    if not geoms:
        raise SimError(f"mesh file {path} has no triangles")
    if len(geoms) == 1:
        geoms = {path.stem: next(iter(geoms.values()))}
    parts, specs = [], {}
    for name, g in geoms.items():
        mat = materials.get(name, materials.get("*"))
        if mat is None:
            raise SimError(f"mesh file {path}: part {name!r} has no material in the material map "
                           f"(parts: {', '.join(geoms)}; use '*' for a default)")
        specs[name] = material_spec(mat)
        # split vertices at edges sharper than 30 degrees: flat faces shade flat, curved scans smooth, and
        # sharp edges carry the duplicated vertices that chips look for
        v, f = trimesh.remesh.subdivide_to_size(np.asarray(g.vertices) * scale, np.asarray(g.faces),
                                                max_edge=MAX_EDGE_M, max_iter=8)
        g = trimesh.graph.smooth_shade(trimesh.Trimesh(v, f, process=False), angle=np.radians(SHARP_EDGE_DEG))
        v = np.asarray(g.vertices, dtype=np.float64)
        parts.append(_part(name, v, np.asarray(g.faces), name))
    return ObjectModel(path.stem, tuple(parts), specs, body=body or parts[0].name)


def object_from_config(mesh: str | None, materials: dict[str, str | dict] | None, scale: float = 1.0,
                       cell_mm: float = 0.5, edge_mm: float = 0.0, edge_shape: str = "chamfer") -> ObjectModel:
    """The brick when ``mesh`` is empty/None, else ``load_mesh``.

    For the brick, ``materials`` replaces the spec of its material keys (``BRICK_MATERIALS``: "plastic" for body and
    studs, "metal" for the plug), e.g. ``{"plastic": {"type": "pplastic", "finish": "smooth", "distribution":
    "ggx"}}``: the same part in another material, or rendered with another microfacet model. Raises SimError for a
    key the brick does not have. ``edge_mm``, ``edge_shape``: the brick's broken edges (``usb_brick``); a user mesh has
    its own."""
    if mesh and edge_mm:
        raise SimError(f"edge_mm: {edge_mm:g} chamfers the brick's edges; the mesh {mesh} brings its own")
    if not mesh:
        brick = usb_brick(cell_mm, edge_mm, edge_shape)
        if not materials:
            return brick
        unknown = sorted(set(materials) - set(brick.materials))
        if unknown:
            raise SimError(f"materials: the brick has material keys {sorted(brick.materials)}, not {unknown}")
        return replace(brick, materials={**brick.materials, **{k: material_spec(v) for k, v in materials.items()}})
    return load_mesh(mesh, materials or {"*": "pplastic"}, scale)


_POSES: dict[int, tuple[ObjectModel, np.ndarray, np.ndarray]] = {}


def _compute_stable_poses(model: ObjectModel) -> tuple[np.ndarray, np.ndarray]:
    import trimesh

    v = np.concatenate([p.vertices for p in model.parts]).astype(np.float64)
    hull = trimesh.Trimesh(v, process=False).convex_hull
    transforms, probs = trimesh.poses.compute_stable_poses(hull, n_samples=1)
    keep = probs > 1e-3
    transforms, probs = transforms[keep], probs[keep]
    return transforms, probs / probs.sum()


def stable_poses(model: ObjectModel) -> tuple[np.ndarray, np.ndarray]:
    """Resting poses on the plane z = 0: (K, 4, 4) object->world transforms and their probabilities (sum 1).

    From trimesh's quasi-static drop model on the convex hull (centre of mass of the hull volume): the
    probability of a pose is the solid angle of initial orientations that end in it. Poses below 0.1 % are
    dropped. The drop height of the paper's Table I does not enter this quasi-static model. An object that
    ``rests_as`` another takes that one's poses.
    """
    if model.rests_as is not None:
        return stable_poses(model.rests_as)
    hit = _POSES.get(id(model))
    if hit is None or hit[0] is not model:
        hit = (model, *_compute_stable_poses(model))
        _POSES[id(model)] = hit
    return hit[1], hit[2]
