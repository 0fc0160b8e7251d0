"""One sample through Mitsuba: the Stokes pass and, only when ground truth is wanted, a 1-spp AOV pass.

Passes (``llvm_ad_mono_polarized`` unless ``sim.variant`` chooses otherwise):
  Stokes  ``stokes`` integrator over ``path`` at ``spp``; box reconstruction filter (lanczos gives S0 < 0 and
          DoLP > 1 at edges). Radiance units; Stokes x axis = image right, as ``model.priors.conventions``.
  AOV     ``aov`` integrator (shape_index, sh_normal, depth) at 1 spp: every pixel shows the surface at one
          point of the pixel, so masks and normals agree with each other and edges are never blends.
          Skipped when ``ground_truth`` is False (a defective sample then gets a shape-index-only pass, for
          its label).
  good    for defects that change geometry, a shape-index pass of the good object's region (geometry only).
Sampling (``RENDERER_VERSION`` 2): correlated multi-jittered pixel samples (``sim.scene.SAMPLER``) and light
sampling in proportion to each emitter's irradiance (``sim.scene.emitter_weights``); version 1 used independent
samples and picked the spot and ambient light with equal probability (same expected image, less than half the
DoLP noise at 16 spp). The glossy ground is ``pplastic`` (polarizing) instead of ``roughplastic`` (which Mitsuba
leaves unpolarized). So a different image for the same seed.
Shape indices are mapped through the scene's own shapes (in JIT variants the index is a process-wide registry
id, not the position in the scene).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from .defects import DEFECT_PART, DefectResult
from .errors import SimError
from .meshes import ObjectModel
from .scene import build_scene, camera_axes, object_to_world, pose_parts, sampler_spp
from .variant import set_variant

NEAR_CLIP_M = 0.01
RENDERER_VERSION = 2
"""Bumped whenever the same seed and config give different pixels (stored in the manifest; resume checks it)."""


@dataclass(frozen=True)
class RenderSettings:
    width: int = 640
    height: int = 480
    spp: int = 16
    ground_truth: bool = True
    max_depth: int = 4
    background_size_m: float = 1.0
    variant: str | None = None
    window: tuple[int, int, int, int] | None = None
    """Render only the block (x0, y0, w, h) of the width x height image (``sim.scene.sensor_dict``); outputs are
    then h x w. For the detectability oracle (``sim.oracle``), which needs only the pixels around a defect."""

    def __post_init__(self) -> None:
        if self.width < 2 or self.height < 2 or self.width % 2 or self.height % 2:
            raise SimError(f"render size must be even and >= 2 (whole 2x2 superpixels), got {self.width}x{self.height}")
        if self.width * self.height > 2448 * 2048 * 4:
            raise SimError(f"render size {self.width}x{self.height} is beyond 4x the native sensor")
        if not 1 <= self.spp <= 65536:
            raise SimError(f"spp must be in [1, 65536], got {self.spp}")
        if sampler_spp(self.spp) != self.spp:
            raise SimError(f"spp {self.spp} is not a count the sampler takes (it would render "
                           f"{sampler_spp(self.spp)}); use sim.scene.sampler_spp")
        if self.max_depth < 2:
            raise SimError(f"max_depth must be >= 2, got {self.max_depth}")


@dataclass
class RenderOutput:
    """Stokes images (H, W) float32 in radiance units; ground truth (None without it): ``normal`` (H, W, 3)
    camera coordinates (x right, y up, z toward the camera; 0 where no surface), ``depth_m`` ray distance
    (0 where no surface), ``part_index`` uint8 (0 = not the object, k = k-th part of the good object; the
    defect counts as its parent part), ``object_mask`` and ``defect_mask`` bool."""

    s0: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    normal: np.ndarray | None = None
    depth_m: np.ndarray | None = None
    part_index: np.ndarray | None = None
    object_mask: np.ndarray | None = None
    defect_mask: np.ndarray | None = None
    seconds: dict[str, float] = field(default_factory=dict)


_INTEGRATORS: dict[tuple, object] = {}


def _integrator(kind: str, max_depth: int = 4):
    import mitsuba as mi

    key = (mi.variant(), kind, max_depth)
    if key not in _INTEGRATORS:
        if kind == "stokes":
            d = {"type": "stokes", "nested": {"type": "path", "max_depth": max_depth}}
        elif kind == "aov":
            d = {"type": "aov", "aovs": "nn:sh_normal,dd:depth,sid:shape_index"}
        else:
            d = {"type": "aov", "aovs": "sid:shape_index"}
        _INTEGRATORS[key] = mi.load_dict(d)
    return _INTEGRATORS[key]


def load_scene(scene_dict: dict):
    """``mi.load_dict`` plus making every scene parameter opaque: Dr.Jit otherwise bakes each scene's values
    (camera pose, colours, roughness) into the kernel as literals and compiles a new kernel (~0.7 s on this
    machine) for every sample; opaque, all scenes of one structure share one cached kernel."""
    import drjit as dr
    import mitsuba as mi

    try:
        scene = mi.load_dict(scene_dict)
    except Exception as exc:
        raise SimError(f"Mitsuba could not build the scene: {exc}") from None
    params = mi.traverse(scene)
    for key in params.keys():
        value = params[key]
        if dr.is_jit_v(value):
            dr.make_opaque(value)
    params.update()
    return scene


def _channels(scene) -> dict[str, np.ndarray]:
    film = scene.sensors()[0].film()
    return {name: np.array(b, dtype=np.float32) for name, b in film.bitmap().split()}


def _first(a: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(a[..., 0] if a.ndim == 3 else a, dtype=np.float32)


LUMINANCE_RGB = (0.212671, 0.715160, 0.072169)
"""Linear sRGB (Rec. 709) -> CIE Y weights, the ones Mitsuba's mono variants reduce an RGB value with."""


def _mono(a: np.ndarray) -> np.ndarray:
    """A film channel as the mono polarization camera sees it. Mono variants write R = G = B (the first is taken,
    bit for bit as before); the spectral fallback writes a colour's R, G and B, whose luminance (CIE Y) is what the
    mono variants render for the same scene. Stokes components are linear in radiance, so each is reduced alike."""
    import mitsuba as mi

    if a.ndim == 3 and "spectral" in mi.variant():
        return np.ascontiguousarray(a[..., :3] @ np.asarray(LUMINANCE_RGB), dtype=np.float32)
    return _first(a)


def shape_ids(scene) -> dict[str, int]:
    """Scene shape key -> the value the ``shape_index`` AOV writes for it (0 = no surface)."""
    import drjit as dr
    import mitsuba as mi

    names = [s.id() for s in scene.shapes()]
    if mi.variant().startswith("scalar"):
        return {n: i + 1 for i, n in enumerate(names)}  # scalar variants write the position + 1
    ids = np.array(dr.reinterpret_array(mi.UInt32, scene.shapes_dr()), dtype=np.int64)
    return dict(zip(names, ids.tolist(), strict=True))


def label_image(sid: np.ndarray, scene, labels: dict[str, int]) -> np.ndarray:
    """shape_index image -> int32 label image (``labels[key]`` for known keys, 0 elsewhere)."""
    ids = shape_ids(scene)
    table = {ids[k]: v for k, v in labels.items() if k in ids}
    out = np.zeros(sid.shape, dtype=np.int32)
    sid_int = np.rint(sid).astype(np.int64)
    for i, v in table.items():
        out[sid_int == i] = v
    return out


def render_sample(model: ObjectModel, params: dict, defect: DefectResult | None, settings: RenderSettings,
                  seed: int, *, empty: bool = False) -> RenderOutput:
    """Render one sampled scene (``sim.scene.sample_scene`` params) with the object ``model`` (or the
    defective one in ``defect``). ``empty``: the same scene (camera, light, background) without the object, for
    frames with no part in view (masks all False, ``part_index`` 0; ``defect`` must be None). Deterministic for a
    given ``seed`` (uint32)."""
    import mitsuba as mi

    if empty and defect is not None:
        raise SimError("an empty scene cannot show a defect")
    set_variant(settings.variant)
    t0 = time.perf_counter()
    shown = defect.model if defect is not None else model
    to_world = object_to_world(params["pose"])
    materials = dict(params["materials"])
    if defect is not None:
        materials[DEFECT_PART] = defect.material
    parts = [] if empty else pose_parts(shown, to_world)
    scene_dict, keys = build_scene(params, parts, materials, settings.width, settings.height, settings.spp,
                                   settings.background_size_m, window=settings.window)
    scene = load_scene(scene_dict)
    t1 = time.perf_counter()
    seed = int(seed) & 0xFFFFFFFF
    mi.render(scene, integrator=_integrator("stokes", settings.max_depth), spp=settings.spp, seed=seed)
    ch = _channels(scene)
    out = RenderOutput(_mono(ch["S0"]), _mono(ch["S1"]), _mono(ch["S2"]))
    t2 = time.perf_counter()
    out.seconds = {"build_s": t1 - t0, "stokes_s": t2 - t1}
    if not settings.ground_truth and defect is None:
        return out
    if "flat_dome" in scene_dict:  # the camera looks through the flat dome: the mask passes see the part, not it
        scene = load_scene({k: v for k, v in scene_dict.items() if k != "flat_dome"})
    # without ground truth a defect still needs its visibility (the label): a shape-index-only pass
    mi.render(scene, integrator=_integrator("aov" if settings.ground_truth else "sid"), spp=1, seed=seed ^ 0x5EED)
    ch = _channels(scene)
    defect_keys = {k: 1 for k, p in zip(keys, parts, strict=True) if p.name == DEFECT_PART}
    out.defect_mask = label_image(ch["sid"], scene, defect_keys) > 0
    if settings.ground_truth:
        part_label = {p.name: i + 1 for i, p in enumerate(model.parts)}
        parent = part_label.get(defect.parent, 0) if defect else 0
        labels = {k: part_label.get(p.name, parent) for k, p in zip(keys, parts, strict=True)}
        out.part_index = label_image(ch["sid"], scene, labels).astype(np.uint8)
        out.object_mask = out.part_index > 0
        hit = np.rint(ch["sid"]) > 0
        nn = ch["nn"].reshape(*ch["sid"].shape[:2], 3).astype(np.float64) @ camera_axes(params["camera"]).T
        length = np.linalg.norm(nn, axis=-1, keepdims=True)
        out.normal = np.where(hit[..., None] & (length > 0), nn / np.maximum(length, 1e-12), 0).astype(np.float32)
        out.depth_m = np.where(hit, _first(ch["dd"]) + NEAR_CLIP_M, 0).astype(np.float32)
    if defect is not None and defect.good_region is not None:
        good_parts = [p for p in shown.parts if p.name != DEFECT_PART] + [defect.good_region]
        good_dict, good_keys = build_scene(params, pose_parts(shown.with_parts(good_parts), to_world), materials,
                                           settings.width, settings.height, 1, settings.background_size_m,
                                           lights=False, window=settings.window)
        good_scene = load_scene(good_dict)
        mi.render(good_scene, integrator=_integrator("sid"), spp=1, seed=seed ^ 0x5EED)
        was = label_image(_channels(good_scene)["sid"], good_scene, {good_keys[-1]: 1}) > 0
        out.defect_mask |= was
    out.seconds["gt_s"] = time.perf_counter() - t2
    return out
