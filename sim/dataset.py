"""Rendered datasets: generating samples, writing them atomically, and reading them back.

Format (contract with drivers' virtual camera and the station's train/eval commands):
  DIR/manifest.json                  format, version, convention_version, renderer_version, width, height, layout,
                                     bit_depth, seed, count, split_rule, config (everything that defines the set),
                                     spp_choice (null, or how ``--dolp-error`` chose ``config.spp``); black_level
                                     (codes, only when the sensor has a pedestal: every reader removes it,
                                     ``model.priors.black_level``)
  DIR/samples/<index:06d>/raw.png    raw mosaic, uint8 or uint16 PNG, codes of ``bit_depth`` bits
  DIR/samples/<index:06d>/raw-K.png  a dome-segment set's (``config.dome_segments``) frame K >= 1 of the part, one
                                     per segment in that order (raw.png is the first)
  DIR/samples/<index:06d>/gt.npz     float32 s0, s1, s2 (noiseless, full-scale units: exposed scene Stokes),
                                     normal (H, W, 3) camera coords (x right, y up, z toward the camera), unit;
                                     object_mask, defect_mask (bool); part_index (uint8); depth (float32, m)
  DIR/samples/<index:06d>/params.json every sampled parameter, "split", "label" (1 iff defect_mask non-empty),
                                     "defect" (null or {"type", ...})
A sample is complete iff its directory exists under its final name: it is written as ``<index>.tmp-<pid>`` and
renamed, so a crash never leaves a half-written sample that looks complete. ``gt.npz`` is a standard npz (zip
of .npy) written with zlib level 1: as small as ``np.savez_compressed`` (level 6) here, at a third of the time.

Determinism: sample ``i`` depends only on the dataset config, ``seed`` and ``i`` (numpy
``default_rng([seed, i])``; Mitsuba's seed is drawn from it), so any index can be re-rendered alone, and shards
(``i % n == k``) can run anywhere in parallel. The pixels also depend on the renderer
(``sim.render.RENDERER_VERSION``, stored in the manifest): resuming a set made by another renderer version is
refused, so one set never mixes two renderers.

Split rule (``SPLIT_RULE``): by index, ``i % 10`` in {0, 1} -> test (20 %, as the paper's 80/20), 2 -> val
(10 % of all, a slice of the paper's training 80 % kept for thresholds), else train. Defects are placed with
probability ``defect_fraction`` in val and test samples only (DRAEM trains on good parts and makes its own
anomalies) unless ``defects_in_train``; a placed defect that is not visible gives label 0. A held-out set
(``DatasetSpec.heldout``, ``HELDOUT_SPLIT_RULE``) puts every sample in test; a validation set
(``DatasetSpec.validation``, ``VALIDATION_SPLIT_RULE``) every sample in val: enough good parts to set a 1 %
threshold, which the 10 % val slice of a training set is not.

Imported sets (``station import``, ``station.datasets``): the same layout, but the split of each sample comes from
the folder it was imported from, not from its index: the manifest's ``split_rule`` is ``FOLDER_SPLIT_RULE`` and
its ``sample_splits`` maps every index (as a string) to its split. Such a set may lack object masks (the station's
region of interest stands in) and defect masks (image-level metrics only); its manifest says which.

Empty samples (``empty_rate`` > 0; ``is_empty``): the same randomised scene (camera, light, background) rendered
without the part, for the station's presence check: ``params.json`` has ``"empty": true`` (the key is absent on
samples that show the part), label 0, no defect, object and defect masks all False. Which indices are empty
follows from the manifest alone (seed, index, ``empty_rate``), in every split; ``Dataset.indices`` leaves them out
unless asked (training and evaluation want parts). With ``empty_rate`` 0 (the default) the manifest's ``config``
has no ``empty_rate`` key, so sets rendered before it existed resume unchanged.
"""

from __future__ import annotations

import json
import math
import os
import shutil
import zipfile
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path
from typing import Any

import cv2
import numpy as np

from model.priors.conventions import CONVENTION_VERSION
from model.priors.photometric import check_segments, mean_stokes

from .defects import DefectConfig, DefectResult, apply_defect
from .errors import SimError
from .meshes import EDGE_SHAPES, ObjectModel, object_from_config
from .oracle import DefectSNR, defect_snr
from .render import RENDERER_VERSION, RenderSettings, render_sample
from .scene import (
    VIEW_CAMERA_KEYS,
    SceneConfig,
    ViewConfig,
    ggx_lobes,
    material_keys_check,
    object_to_world,
    sample_scene,
    sampler_spp,
    second_view,
)
from .sensor import SensorConfig, simulate
from .variation import LineVariation

FORMAT = "polar-ano-dataset"
VERSION = 1
SPLIT_RULE = ("index % 10 in {0, 1}: test; index % 10 == 2: val (slice of the 80 % train part, for thresholds); "
              "else train. Defects only in val/test unless defects_in_train.")
HELDOUT_SPLIT_RULE = "every sample: test (a held-out evaluation set: nothing in it trains or selects a model)"
VALIDATION_SPLIT_RULE = "every sample: val (a validation set: thresholds, calibration and selection, never training)"
WHOLE_SET_RULES = {"test": HELDOUT_SPLIT_RULE, "val": VALIDATION_SPLIT_RULE}
"""A set whose every sample is in one split: that split -> the manifest's ``split_rule``."""
FOLDER_SPLIT_RULE = "folders"
"""``split_rule`` of an imported set: splits from the source folders, per sample in the manifest's ``sample_splits``."""
GT_KEYS = ("s0", "s1", "s2", "normal", "object_mask", "defect_mask", "part_index", "depth")


def split_of(index: int, whole: str | None = None) -> str:
    """The split of sample ``index`` (see ``SPLIT_RULE``); ``whole`` in a set whose every sample is in that split
    (``WHOLE_SET_RULES``: a held-out or a validation set)."""
    if whole:
        return whole
    r = index % 10
    return "test" if r in (0, 1) else "val" if r == 2 else "train"


@dataclass(frozen=True)
class DatasetSpec:
    """Everything that defines a rendered set; stored as the manifest's ``config``."""

    seed: int = 0
    width: int = 640
    height: int = 480
    spp: int = 16
    max_depth: int = 4
    ground_truth: bool = True
    defect_fraction: float = 0.5
    defects_in_train: bool = False
    empty_rate: float = 0.0
    """Fraction of samples rendered without the part (see ``is_empty``); 0 = none."""
    visibility: bool = False
    """Measure every placed defect's detectability (``sim.oracle``) into ``params.json``'s ``defect``."""
    heldout: bool = False
    """Every sample in the test split (``HELDOUT_SPLIT_RULE``): an evaluation set, rendered with its own seed."""
    validation: bool = False
    """Every sample in the val split (``VALIDATION_SPLIT_RULE``): thresholds and selection, rendered with its own
    seed."""
    mesh: str = ""
    materials: dict[str, Any] = field(default_factory=dict)
    mesh_scale: float = 1.0
    edge_mm: tuple[float, float] = (0.0, 0.0)
    """The brick's body edges chamfered at 45 degrees that far back along each face (``sim.meshes.usb_brick``), in
    mm: one value (a number, or lo == hi) for every part, or a range drawn per part to 0.01 mm (``part_of``) on the
    sample's own stream ``default_rng([seed, index, 6])``, so every other draw stays. (0, 0): sharp, as designed."""
    edge_shape: str = "chamfer"
    """How ``edge_mm`` breaks the edges (``sim.meshes.EDGE_SHAPES``): "chamfer" (45 degrees) or "round" (a fillet of
    that radius, shaded smooth; a chip needs a crease, so a set of round edges leaves chips out of its types)."""
    variant: str | None = None
    scene: SceneConfig = field(default_factory=SceneConfig)
    defects: DefectConfig = field(default_factory=DefectConfig)
    sensor: SensorConfig = field(default_factory=SensorConfig)
    variation: LineVariation = field(default_factory=LineVariation)
    dome_segments: tuple[float, ...] = ()
    """Photometric stereo: one frame per segment of a segmented dome, lit in turn, for every sample. Each entry is
    the lit segment's azimuth (``scene.ambient_gradient_azimuth_deg``: degrees from world +x toward +y, image right
    on the line presets); the scene's ``ambient_gradient`` sets how much brighter the lit side is. Empty (default):
    one frame per sample under the scene's dome. See ``generate_sample`` for what the frames share."""

    view: dict[str, Any] = field(default_factory=dict)
    """A second camera of the station (``[view]``: any of ``VIEW_KEYS``: the scene's camera ranges, a height above
    the belt, a flat dome; ``sim.scene.ViewConfig``): each sample is drawn exactly as without it, the defect placed
    for the line's camera, then seen from a camera drawn from these ranges on the sample's own stream
    ``default_rng([seed, index, 5])`` (``sim.scene.second_view``). The same seed with and without ``view`` renders
    the same parts, defects, light and sensor draws from two cameras. Empty: the line's camera."""

    def __post_init__(self) -> None:
        bad = sorted(set(self.view) - set(VIEW_KEYS))
        if bad:
            raise SimError(f"view: unknown keys {bad}; use {', '.join(VIEW_KEYS)}")
        if self.view:
            try:
                self.view_config()  # checks the ranges
            except SimError as exc:
                raise SimError(f"view: {exc}") from None
        # the config states the spp that is rendered: the sampler rounds some counts up (32 -> 35)
        object.__setattr__(self, "spp", sampler_spp(self.spp) if self.spp >= 1 else self.spp)
        if not 0.0 <= self.defect_fraction <= 1.0:
            raise SimError(f"defect fraction must be in [0, 1], got {self.defect_fraction}")
        if not 0.0 <= self.empty_rate <= 1.0:
            raise SimError(f"empty rate must be in [0, 1], got {self.empty_rate}")
        if self.seed < 0:
            raise SimError(f"seed must be >= 0, got {self.seed}")
        if not (math.isfinite(self.mesh_scale) and self.mesh_scale > 0):
            raise SimError(f"mesh_scale must be a number > 0, got {self.mesh_scale}")
        edge = self.edge_mm
        edge = (edge, edge) if isinstance(edge, int | float) and not isinstance(edge, bool) else edge
        try:
            lo, hi = (float(x) for x in edge)
        except (TypeError, ValueError):
            raise SimError(f"edge_mm must be a number or a range [lo, hi] in [0, 2] (mm), got {edge!r}") from None
        if not (math.isfinite(lo) and math.isfinite(hi) and 0 <= lo <= hi <= 2):
            raise SimError(f"edge_mm must be a number or a range [lo, hi] in [0, 2] (mm), got {self.edge_mm!r}")
        object.__setattr__(self, "edge_mm", (lo, hi))
        if self.mesh and hi:
            raise SimError(f"edge_mm: {hi:g} chamfers the brick's edges; the mesh {self.mesh} brings its own")
        if self.edge_shape not in EDGE_SHAPES:
            raise SimError(f"edge_shape must be one of {', '.join(EDGE_SHAPES)}, got {self.edge_shape!r}")
        if self.edge_shape == "round" and hi and self.defect_fraction and "chip" in self.defects.types:
            raise SimError("edge_shape round: a chip cuts a crease and a rounded edge has none; name the other "
                           "types in [defects] types")
        if self.heldout and self.validation:
            raise SimError("a set is held out (every sample test) or a validation set (every sample val), not both")
        try:
            object.__setattr__(self, "dome_segments", check_segments(self.dome_segments))
        except ValueError as exc:
            raise SimError(f"dome_segments {exc}") from None
        if self.variation.panel_scale and not self.scene.ring_radiance:
            raise SimError("variation.panel_scale needs a panel or ring light to scale (scene.ring_radiance > 0)")
        if self.dome_segments:
            if not self.scene.ambient_gradient:
                raise SimError("dome_segments need scene.ambient_gradient > 0 (how much brighter the lit segment "
                               "is): under a uniform dome every segment's frame is the same")
        self.render_settings()  # checks size and spp

    def view_config(self) -> ViewConfig:
        """The second camera (``view``): its ranges in place of the line camera's, its height above the belt and
        its flat dome (``sim.scene.ViewConfig``)."""
        return ViewConfig.from_dict(self.view, self.scene)

    @property
    def whole_split(self) -> str | None:
        """The split every sample is in (``WHOLE_SET_RULES``), None for the index rule (``SPLIT_RULE``)."""
        return "test" if self.heldout else "val" if self.validation else None

    def render_settings(self) -> RenderSettings:
        return RenderSettings(self.width, self.height, self.spp, self.ground_truth, self.max_depth,
                              self.scene.background_size_m, self.variant)

    def oracle_settings(self) -> RenderSettings:
        """The detectability oracle's renders: half the sample's spp each (four of them: two pairs)."""
        return RenderSettings(self.width, self.height, sampler_spp(max(1, self.spp // 2)), False, self.max_depth,
                              self.scene.background_size_m, self.variant)

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["scene"] = self.scene.to_dict()
        d.pop("variant")  # the variant changes speed, not the distribution of samples
        if not d["empty_rate"]:
            d.pop("empty_rate")  # manifests of sets without empty samples stay as they were before the key
        for key in ("visibility", "heldout", "validation", "dome_segments", "view"):
            if not d[key]:
                d.pop(key)  # likewise for sets without the detectability oracle or a whole-set split
        lo, hi = self.edge_mm
        if hi == 0:
            d.pop("edge_mm")  # and for sets of the sharp brick
        elif lo == hi:
            d["edge_mm"] = lo  # one edge for every part, as first written
        if self.edge_shape == "chamfer" or hi == 0:
            d.pop("edge_shape")  # and for sets of chamfered or sharp edges, as first written
        if not self.variation.active:
            d.pop("variation")  # and for sets without line variation
        else:
            d["variation"] = self.variation.to_dict()
        return json.loads(json.dumps(d))  # tuples -> lists, as read back from JSON

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> DatasetSpec:
        d = dict(d)
        scene = SceneConfig.from_dict(d.pop("scene", {}))
        defects = DefectConfig.from_dict(d.pop("defects", {}))
        variation = LineVariation.from_dict(d.pop("variation", {}) or {})
        sensor_d = d.pop("sensor", {})
        try:
            sensor = SensorConfig(**sensor_d)
        except TypeError as exc:
            raise SimError(f"sensor: {exc}") from None
        try:
            return cls(**d, scene=scene, defects=defects, sensor=sensor, variation=variation)
        except TypeError as exc:
            raise SimError(f"dataset config: {exc}") from None


@dataclass
class Sample:
    """One sample. ``raw``: (H, W) uint8/uint16 mosaic. Ground truth fields are None when not rendered; see the
    module docstring for units and conventions."""

    index: int
    raw: np.ndarray
    params: dict[str, Any]
    label: int
    split: str
    s0: np.ndarray | None = None
    s1: np.ndarray | None = None
    s2: np.ndarray | None = None
    normal: np.ndarray | None = None
    object_mask: np.ndarray | None = None
    defect_mask: np.ndarray | None = None
    part_index: np.ndarray | None = None
    depth: np.ndarray | None = None
    segment_raws: tuple[np.ndarray, ...] = ()
    """A dome-segment set's frames (``DatasetSpec.dome_segments`` order; the first is ``raw``); empty otherwise."""

    @property
    def raws(self) -> tuple[np.ndarray, ...]:
        """Every frame of the part: one per dome segment, or ``(raw,)``."""
        return self.segment_raws or (self.raw,)


OVERRIDE_SECTIONS = ("scene", "defects", "sensor", "variation", "view")
VIEW_KEYS = (*VIEW_CAMERA_KEYS, "camera_height_m", "flat_dome_radiance", "flat_dome_distance_m", "flat_dome_width_m",
             "flat_dome_top_m", "flat_dome_fringe_period_m", "flat_dome_fringe_depth", "flat_dome_fringe_phase_deg")
"""The keys of ``[view]`` (``DatasetSpec.view``): a second camera's ranges, as the scene's camera keys; its height
above the belt, for a camera that looks level at the part; a flat dome it looks through, with stripes across it or not
(``sim.scene.ViewConfig``, ``FlatDome``)."""


def read_overrides(path: str | Path) -> dict[str, dict[str, Any]]:
    """A JSON or TOML file of ``[scene]``, ``[defects]``, ``[sensor]``, ``[variation]``, ``[view]`` overrides
    (``station render --config``, ``sim/presets/*.toml``), for ``DatasetSpec.from_dict``; a missing, unparsable
    or unknown-section file is a SimError naming it."""
    path = Path(path)
    if not path.is_file():
        raise SimError(f"--config {path}: no such file")
    try:
        if path.suffix == ".toml":
            import tomllib

            extra = tomllib.loads(path.read_text())
        else:
            extra = json.loads(path.read_text())
    except Exception as exc:
        raise SimError(f"--config {path}: cannot parse ({exc})") from None
    bad = sorted(set(extra) - set(OVERRIDE_SECTIONS))
    if bad:
        raise SimError(f"--config {path}: unknown sections {bad}; use {', '.join(OVERRIDE_SECTIONS)}")
    return extra


def read_layers(paths: Sequence[str | Path]) -> dict[str, dict[str, Any]]:
    """Override files read and layered in order (``station render --config A --config B``): ``merge_overrides`` of
    ``read_overrides`` of each; {} for none."""
    return merge_overrides([read_overrides(path) for path in paths])


def merge_overrides(layers: list[dict[str, dict[str, Any]]]) -> dict[str, dict[str, Any]]:
    """Override files layered in order: per section, a later file's keys replace an earlier one's."""
    out: dict[str, dict[str, Any]] = {}
    for layer in layers:
        for section, values in layer.items():
            out[section] = {**out.get(section, {}), **values}
    return out


def prepare(spec: DatasetSpec) -> ObjectModel:
    """Load and check everything a render needs (mesh, materials, defect types) before rendering anything;
    raises SimError naming the file, key or material."""
    from .variant import set_variant

    set_variant(spec.variant)
    model = object_from_config(spec.mesh, spec.materials, spec.mesh_scale, edge_mm=spec.edge_mm[0],
                               edge_shape=spec.edge_shape)
    material_keys_check(model)
    if spec.defect_fraction > 0:
        usable = spec.defects.usable_types(model)
        if not usable:
            raise SimError(f"none of the defect types {list(spec.defects.types)} is possible on {model.name!r}")
        for kind in usable:  # dry run on a camera straight above: errors now, not at sample 3,000
            apply_defect(model, kind, np.random.default_rng(0), spec.defects, np.array([0.0, 0.0, 1.0]),
                         {k: {**v, "colour": [0.5] * 3, "alpha": 0.1} for k, v in model.materials.items()})
    return model


def is_empty(seed: int, index: int, empty_rate: float) -> bool:
    """Whether sample ``index`` of a set with this ``seed`` and ``empty_rate`` is rendered without the part. Its
    own random stream (``default_rng([seed, index, 2])``), so the samples that show the part are the same
    whatever ``empty_rate`` is."""
    return empty_rate > 0 and bool(np.random.default_rng([seed, index, 2]).random() < empty_rate)


@dataclass(frozen=True)
class SampleDraw:
    """Everything random about sample ``index`` before rendering: scene parameters, the defect (or None), the
    Mitsuba seed, split, whether the part is left out, and the sensor (with the line's variation drawn)."""

    index: int
    split: str
    params: dict[str, Any]
    defect: DefectResult | None
    mitsuba_seed: int
    empty: bool
    sensor: SensorConfig
    sensor_record: dict[str, float]
    part: ObjectModel
    """The part this sample shows (``part_of``): the prepared model, or its chamfer drawn for this sample."""
    edge_mm: float | None = None
    """The chamfer (or round: ``DatasetSpec.edge_shape``) drawn for this sample (``params.json``'s ``edge_mm``);
    None when every part has the spec's."""


_PARTS: dict[tuple[str, float], ObjectModel] = {}
"""Parts built for a drawn chamfer (``part_of``), by the spec's object keys and the chamfer: each is built, and its
resting poses found (about a second), once per process."""


def part_of(spec: DatasetSpec, model: ObjectModel, index: int) -> tuple[ObjectModel, float | None]:
    """Sample ``index``'s part and its chamfer in mm: ``model`` (prepared for ``spec``) and None, unless
    ``spec.edge_mm`` is a range, when the chamfer is drawn on ``default_rng([seed, index, 6])`` to 0.01 mm."""
    lo, hi = spec.edge_mm
    if lo == hi:
        return model, None
    edge = round(float(np.random.default_rng([spec.seed, index, 6]).uniform(lo, hi)), 2)
    key = (json.dumps([spec.mesh, spec.materials, spec.mesh_scale, spec.edge_shape], sort_keys=True), edge)
    if key not in _PARTS:
        _PARTS[key] = object_from_config(spec.mesh, spec.materials, spec.mesh_scale, edge_mm=edge,
                                         edge_shape=spec.edge_shape)
    return _PARTS[key], edge


def draw_sample(spec: DatasetSpec, model: ObjectModel, index: int) -> SampleDraw:
    """Draw sample ``index``'s scene and defect (deterministic in ``spec.seed`` and ``index``) on its part
    (``part_of``)."""
    model, edge = part_of(spec, model, index)
    rng = np.random.default_rng([spec.seed, index])
    split = split_of(index, spec.whole_split)
    params = sample_scene(rng, spec.scene, model)  # an empty sample keeps the camera and light aimed at the pose
    if spec.scene.ggx_share and np.random.default_rng([spec.seed, index, 7]).random() < spec.scene.ggx_share:
        params["materials"] = ggx_lobes(params["materials"])  # before a defect copies a material
    panel = spec.variation.panel(spec.seed, index)
    if panel is not None:  # the line's variation of the panel (``LineVariation.panel_scale``), recorded in the scene
        params["ring_radiance"] *= panel
        params["panel_scale"] = panel
    empty = is_empty(spec.seed, index, spec.empty_rate)
    defect = None
    wants_defect = (split != "train" or spec.defects_in_train) and not empty
    if wants_defect and rng.random() < spec.defect_fraction:
        kind = str(rng.choice(list(spec.defects.usable_types(model))))
        to_world = object_to_world(params["pose"])
        cam_obj = np.linalg.solve(to_world, np.r_[params["camera"]["origin"], 1.0])[:3]
        defect = apply_defect(model, kind, rng, spec.defects, cam_obj, params["materials"])
    if spec.view:  # a second camera of the same part: everything above drawn as for the line's camera
        params = second_view(params, spec.view_config(), model, np.random.default_rng([spec.seed, index, 5]))
    sensor, sensor_record = spec.variation.draw(spec.sensor, spec.seed, index)
    return SampleDraw(index, split, params, defect, int(rng.integers(2**32)), empty, sensor, sensor_record, model,
                      edge)


def oracle_record(result: DefectSNR) -> dict[str, Any]:
    """The oracle's keys in ``params.json``'s ``defect``: ``snr`` and ``snr_demosaic`` per prior, ``snr_best`` (the
    camera prior with the largest snr) and ``snr_oracle`` (pixels, spp per oracle render, seconds)."""
    d = result.to_dict()
    return {"snr": d["snr"], "snr_demosaic": d["snr_demosaic"], "snr_best": d["best"],
            "snr_oracle": {"pixels": d["pixels"], "spp": d["spp"], "seconds": d["seconds"]}}


def segment_seeds(spec: DatasetSpec, index: int, mitsuba_seed: int) -> list[int]:
    """The Mitsuba seed of each dome segment's frame of sample ``index``: the sample's own for the first (so a
    segment set's first frames are the one-frame set rendered under that segment), then independent draws: two
    exposures of a part have independent noise, and correlated noise would flatter their difference."""
    return [mitsuba_seed] + [int(np.random.default_rng([spec.seed, index, 2, k]).integers(2**32))
                             for k in range(1, len(spec.dome_segments))]


def generate_sample(spec: DatasetSpec, model: ObjectModel, index: int) -> Sample:
    """Render sample ``index`` in memory (deterministic in ``spec.seed`` and ``index``); with
    ``spec.visibility`` also measure its defect's detectability (``sim.oracle``).

    With ``spec.dome_segments`` the part is rendered once per segment: the same draws (part, pose, defect, camera,
    stray light, exposure and gain), the dome lit on that segment's side, independent render and sensor noise
    (``segment_seeds``; the sensor's rng ``[seed, index, 1, k]``, the first frame's ``[seed, index, 1]``). The
    ground-truth Stokes are the frames' mean (the uniform dome's); masks and normals are the first frame's (the
    geometry is the same)."""
    draw = draw_sample(spec, model, index)
    params, defect, mi_seed, split, empty = draw.params, draw.defect, draw.mitsuba_seed, draw.split, draw.empty
    model = draw.part
    settings = spec.render_settings()
    segments: tuple[float | None, ...] = spec.dome_segments or (None,)
    seeds = segment_seeds(spec, index, mi_seed)
    outs, frames = [], []
    for k, azimuth in enumerate(segments):
        lit = params if azimuth is None else {**params, "ambient_gradient_azimuth_deg": azimuth}
        out_k = render_sample(model, lit, defect, settings if k == 0 else replace(settings, ground_truth=False),
                              seeds[k], empty=empty)
        noise = np.random.default_rng([spec.seed, index, 1] if k == 0 else [spec.seed, index, 1, k])
        outs.append(out_k)
        frames.append(simulate(out_k.s0, out_k.s1, out_k.s2, draw.sensor, noise))
    out, frame = outs[0], frames[0]
    label = int(out.defect_mask is not None and bool(out.defect_mask.any()))
    record = {"index": index, "split": split, "label": label, "defect": defect.info if defect else None,
              "mitsuba_seed": mi_seed, "scene": params, "render_seconds": out.seconds,
              "n_saturated": frame.n_saturated}
    if spec.dome_segments:
        record["dome_segments"] = [{"azimuth_deg": a, "mitsuba_seed": sd, "n_saturated": f.n_saturated,
                                    "render_seconds": o.seconds}
                                   for a, sd, f, o in zip(spec.dome_segments, seeds, frames, outs, strict=True)]
    if draw.sensor_record:
        record["sensor"] = draw.sensor_record
    if draw.edge_mm is not None:
        record["edge_mm"] = draw.edge_mm
    if empty:
        record["empty"] = True
    if defect is not None and out.defect_mask is not None:
        record["defect"]["visible_px"] = int(out.defect_mask.sum())
        if spec.visibility:
            result, _ = defect_snr(model, params, defect, spec.oracle_settings(), mi_seed, draw.sensor,
                                   out.defect_mask)
            record["defect"].update(oracle_record(result))
            record["render_seconds"] = {**out.seconds, "oracle_s": result.seconds}
    sample = Sample(index, frame.raw, record, label, split,
                    segment_raws=tuple(f.raw for f in frames) if spec.dome_segments else ())
    if spec.ground_truth:
        sample.s0, sample.s1, sample.s2 = mean_stokes([(f.s0, f.s1, f.s2) for f in frames])
        sample.normal, sample.object_mask, sample.defect_mask = out.normal, out.object_mask, out.defect_mask
        sample.part_index, sample.depth = out.part_index, out.depth_m
    return sample


def frame_file(k: int) -> str:
    """File of a sample's frame ``k``: ``raw.png``, then ``raw-1.png``... for a dome-segment set's later frames."""
    return "raw.png" if k == 0 else f"raw-{k}.png"


def sample_dir(root: str | Path, index: int) -> Path:
    return Path(root) / "samples" / f"{index:06d}"


def defect_records(root: str | Path, indices: Sequence[int]) -> list[dict[str, Any] | None]:
    """Each sample's ``params.json`` ``defect`` record (None for a good part)."""
    out = []
    for i in indices:
        params = json.loads((sample_dir(root, i) / "params.json").read_text())
        out.append(params.get("defect") if params.get("label") else None)
    return out


def write_sample(root: str | Path, sample: Sample) -> Path:
    """Write ``sample`` under ``root`` atomically (temporary directory, fsync, rename); returns its folder."""
    final = sample_dir(root, sample.index)
    tmp = final.with_name(f"{final.name}.tmp-{os.getpid()}")
    if tmp.exists():
        shutil.rmtree(tmp)
    tmp.mkdir(parents=True)
    for k, raw in enumerate(sample.raws):
        name = frame_file(k)
        if not cv2.imwrite(str(tmp / name), raw):
            raise SimError(f"could not write {tmp / name}")
    gt = {k: getattr(sample, k) for k in GT_KEYS if getattr(sample, k) is not None}
    if gt:
        save_npz(tmp / "gt.npz", gt)
    (tmp / "params.json").write_text(json.dumps(sample.params, indent=1))
    for f in tmp.iterdir():
        with open(f, "rb") as fh:
            os.fsync(fh.fileno())
    if final.exists():  # another shard finished it meanwhile: same content by determinism
        shutil.rmtree(tmp)
        return final
    os.rename(tmp, final)
    return final


def save_npz(path: str | Path, arrays: dict[str, np.ndarray]) -> None:
    """``np.savez_compressed`` with zlib level 1 (numpy fixes level 6): the same npz format, ``np.load`` reads it.
    Measured on a 640x480 gt: 0.08 s and 2.24 MB against 0.22 s and 2.21 MB (depth and S0 barely compress)."""
    with zipfile.ZipFile(path, "w", compression=zipfile.ZIP_DEFLATED, compresslevel=1) as zf:
        for key, value in arrays.items():
            with zf.open(f"{key}.npy", "w", force_zip64=True) as fh:
                np.lib.format.write_array(fh, np.asanyarray(value), allow_pickle=False)


IGNORED_ON_RESUME = ("count", "spp_choice", "visibility")
"""Manifest keys, and keys of its ``config``, that may differ when resuming: how spp was chosen does not change the
samples (spp does), nor does the detectability oracle (``--visibility``), which measures each sample it renders after
it; its summary (the manifest's ``visibility``) counts the samples it measured (``n`` per type)."""


def manifest_for(spec: DatasetSpec, count: int, spp_choice: dict[str, Any] | None = None) -> dict[str, Any]:
    return {"format": FORMAT, "version": VERSION, "convention_version": CONVENTION_VERSION,
            "renderer_version": RENDERER_VERSION, "width": spec.width, "height": spec.height,
            "layout": spec.sensor.layout, "bit_depth": spec.sensor.bit_depth, "seed": spec.seed, "count": count,
            "split_rule": WHOLE_SET_RULES.get(spec.whole_split or "", SPLIT_RULE), "config": spec.to_dict(),
            "spp_choice": spp_choice,
            **({"black_level": spec.sensor.black_level_dn} if spec.sensor.black_level_dn else {})}


def init_dataset(root: str | Path, spec: DatasetSpec, count: int, spp_choice: dict[str, Any] | None = None
                 ) -> dict[str, Any]:
    """Create ``root`` and its manifest, or check that an existing one describes the same set (resume): same
    renderer version, seed and config. Removes temporary sample folders of processes that no longer run."""
    root = Path(root)
    manifest = manifest_for(spec, count, spp_choice)
    path = root / "manifest.json"
    if path.exists():
        old = read_manifest(path)
        old_renderer = old.get("renderer_version", 1)  # sets from before the key existed are version 1
        if old_renderer != RENDERER_VERSION:
            raise SimError(f"{path}: the set was rendered by renderer version {old_renderer}, this code renders "
                           f"version {RENDERER_VERSION} (different pixels for the same seed); resuming would mix "
                           f"the two: render into a new --out, or finish the set with the older code")
        if _comparable(old) != _comparable(manifest):
            raise SimError(f"{path} describes a different dataset (seed or config differ); use another --out or "
                           f"the same options")
        if old.get("count", 0) >= count:
            manifest = old
        elif "visibility" in old:  # what the oracle measured stays until a render with it summarises again
            manifest["visibility"] = old["visibility"]
    (root / "samples").mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f"manifest.json.tmp-{os.getpid()}")
    tmp.write_text(json.dumps(manifest, indent=1))
    os.replace(tmp, path)
    for stale in (root / "samples").glob("*.tmp-*"):
        pid = stale.name.rsplit("-", 1)[-1]
        if pid.isdigit() and not _alive(int(pid)):
            shutil.rmtree(stale, ignore_errors=True)
    return manifest


def _comparable(manifest: dict[str, Any]) -> dict[str, Any]:
    """What a resume compares of a manifest: every key but ``IGNORED_ON_RESUME``'s, in its config too, the config as
    this code writes it (``_normalized_config``); a set from before ``renderer_version`` existed is version 1."""
    out = {"renderer_version": 1, **{k: v for k, v in manifest.items() if k not in IGNORED_ON_RESUME}}
    config = _normalized_config(out.get("config", {}))
    out["config"] = {k: v for k, v in config.items() if k not in IGNORED_ON_RESUME}
    return out


def _normalized_config(config: dict[str, Any]) -> dict[str, Any]:
    """A manifest's config as this code writes it: a key the set's code wrote at its default, or did not know yet
    (its default draws what that code drew), reads the same either way. As written when it does not parse."""
    try:
        return DatasetSpec.from_dict(config).to_dict()
    except (SimError, TypeError, ValueError):
        return config


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return False  # our own leftovers are from an earlier run that reused the pid
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def is_complete(root: str | Path, index: int) -> bool:
    return sample_dir(root, index).is_dir()


def render_set(root: str | Path, spec: DatasetSpec, count: int, shard: tuple[int, int] = (0, 1),
               spp_choice: dict[str, Any] | None = None, progress: bool = True) -> int:
    """Render the samples ``i % n == k`` (shard ``(k, n)``) of a ``count``-sample set into ``root``, skipping
    finished ones (resume), with a progress bar; returns how many were rendered. Input errors surface before
    the first render (``prepare``)."""
    import time

    from tqdm import tqdm

    model = prepare(spec)
    init_dataset(root, spec, count, spp_choice)
    k, n = shard
    mine = [i for i in range(count) if i % n == k]
    todo = [i for i in mine if not is_complete(root, i)]
    print(f"rendering {len(todo)} of {len(mine)} samples (shard {k}/{n}) into {root}; "
          f"{len(mine) - len(todo)} already done")
    labels = {0: 0, 1: 0}
    n_empty = 0
    t0 = time.perf_counter()
    with tqdm(total=len(mine), initial=len(mine) - len(todo), unit="sample", dynamic_ncols=True,
              disable=not progress) as bar:
        for i in todo:
            sample = generate_sample(spec, model, i)
            write_sample(root, sample)
            labels[sample.label] += 1
            n_empty += bool(sample.params.get("empty"))
            bar.update(1)
    dt = time.perf_counter() - t0
    if todo:
        print(f"rendered {len(todo)} samples in {dt:.1f} s ({dt / len(todo):.2f} s/sample); "
              f"{labels[1]} with a visible defect" + (f", {n_empty} without the part (empty)" if n_empty else ""))
    if spec.visibility:
        write_visibility_summary(root)
    return len(todo)


def write_visibility_summary(root: str | Path) -> dict[str, Any]:
    """Summarise the oracle values of every complete sample (``sim.detectability.summarise``) into the manifest's
    ``visibility`` key (atomically; any shard may run it, the last one sees all samples); returns the manifest."""
    from .detectability import VISIBLE_SNR, read_records, summarise

    path = Path(root) / "manifest.json"
    manifest = json.loads(path.read_text())
    manifest["visibility"] = {"threshold_snr": VISIBLE_SNR, "by_type": summarise(read_records(root)),
                              "see": "sim/oracle.py (matched-filter SNR against sensor noise, paired renders)"}
    tmp = path.with_name(f"manifest.json.tmp-{os.getpid()}")
    tmp.write_text(json.dumps(manifest, indent=1, default=float))
    os.replace(tmp, path)
    return manifest


def read_manifest(path: Path) -> dict[str, Any]:
    """A set's ``manifest.json``; SimError naming the file (and key) unless it is a JSON object whose ``bit_depth``
    (when present) is an integer in 1..16 and ``layout`` a known mosaic layout."""
    from model.priors import LAYOUTS
    from model.priors.conventions import is_bit_depth

    try:
        manifest = json.loads(path.read_text())
    except (OSError, ValueError) as exc:  # ValueError: not JSON, or not UTF-8
        raise SimError(f"{path}: unreadable manifest ({exc})") from None
    if not isinstance(manifest, dict):
        raise SimError(f"{path}: expected a JSON object, got {type(manifest).__name__}")
    depth = manifest.get("bit_depth")
    if depth is not None and not is_bit_depth(depth):
        raise SimError(f"{path}: bit_depth: {depth!r} is not an integer in 1..16")
    layout = manifest.get("layout")
    if layout is not None and layout not in LAYOUTS:
        raise SimError(f"{path}: layout: {layout!r} is not one of {', '.join(LAYOUTS)}")
    return manifest


class Dataset:
    """A rendered set on disk (read only). ``len`` counts complete samples."""

    def __init__(self, root: str | Path):
        self.root = Path(root)
        path = self.root / "manifest.json"
        if not path.is_file():
            raise SimError(f"{self.root} is not a rendered dataset: {path} is missing (run station render)")
        self.manifest = read_manifest(path)
        if self.manifest.get("format") != FORMAT or self.manifest.get("version") != VERSION:
            raise SimError(f"{path}: not a {FORMAT} version {VERSION} manifest")
        if self.manifest.get("convention_version") != CONVENTION_VERSION:
            raise SimError(f"{path}: rendered with convention version {self.manifest.get('convention_version')}, "
                           f"this code uses {CONVENTION_VERSION}: re-render")
        self._indices = sorted(int(p.name) for p in (self.root / "samples").glob("[0-9]" * 6) if p.is_dir())
        self._splits: dict[int, str] | None = None
        self._whole = {rule: split for split, rule in WHOLE_SET_RULES.items()}.get(self.manifest.get("split_rule", ""))
        """The split every sample is in (a held-out or validation set), else None."""
        if self.manifest.get("split_rule") == FOLDER_SPLIT_RULE:
            try:
                self._splits = {int(k): str(v) for k, v in self.manifest["sample_splits"].items()}
            except (KeyError, AttributeError, ValueError) as exc:
                raise SimError(f"{path}: split rule {FOLDER_SPLIT_RULE!r} without a valid sample_splits map "
                               f"({exc})") from None
        config = self.manifest.get("config") or {}
        self.dome_segments = tuple(float(a) for a in config.get("dome_segments") or ())
        """Azimuths of the dome segments each part was imaged under, one frame each (``DatasetSpec.dome_segments``);
        empty: one frame per part."""
        self.empty_rate = float(config.get("empty_rate", 0.0))
        """Fraction of samples rendered without the part (0 for sets from before the key)."""
        seed = int(config.get("seed", self.manifest.get("seed", 0)))
        self._empty = {i for i in self._indices if is_empty(seed, i, self.empty_rate)}

    def __len__(self) -> int:
        return len(self._indices)

    def indices(self, split: str | None = None, empty: bool | None = False) -> list[int]:
        """Complete sample indices, all or of one split ("train", "val", "test"). ``empty``: False (default) only
        samples that show the part, True only the empty ones, None both."""
        if split not in (None, "train", "val", "test"):
            raise SimError(f"unknown split {split!r}; use train, val or test")
        return [i for i in self._indices if (split is None or self.split(i) == split)
                and (empty is None or (i in self._empty) == empty)]

    def split(self, index: int) -> str:
        """The split of sample ``index``: from the manifest for an imported set, else ``split_of``."""
        if self._splits is not None:
            return self._splits.get(index, "")
        return split_of(index, self._whole)

    def load(self, index: int, ground_truth: bool = True) -> Sample:
        d = sample_dir(self.root, index)
        if not d.is_dir():
            raise SimError(f"{self.root}: sample {index} is missing or incomplete ({d})")
        raw = cv2.imread(str(d / "raw.png"), cv2.IMREAD_UNCHANGED)
        if raw is None or raw.ndim != 2:
            raise SimError(f"{d / 'raw.png'}: missing or not a single-channel PNG")
        try:
            params = json.loads((d / "params.json").read_text())
        except (OSError, json.JSONDecodeError) as exc:
            raise SimError(f"{d / 'params.json'}: unreadable ({exc})") from None
        later = []
        for k in range(1, len(self.dome_segments)):
            more = cv2.imread(str(d / frame_file(k)), cv2.IMREAD_UNCHANGED)
            if more is None or more.shape != raw.shape:
                raise SimError(f"{d / frame_file(k)}: missing or not the shape of raw.png (a set of "
                               f"{len(self.dome_segments)} frames per part: manifest dome_segments)")
            later.append(more)
        sample = Sample(index, raw, params, int(params["label"]), params["split"],
                        segment_raws=(raw, *later) if later else ())
        if ground_truth and (d / "gt.npz").is_file():
            try:
                with np.load(d / "gt.npz") as gt:
                    for k in GT_KEYS:
                        if k in gt:
                            setattr(sample, k, gt[k])
            except (OSError, ValueError) as exc:
                raise SimError(f"{d / 'gt.npz'}: unreadable ({exc})") from None
        return sample


def open_dataset(root: str | Path) -> Dataset:
    return Dataset(root)
