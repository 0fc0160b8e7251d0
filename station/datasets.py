"""Datasets as the model sees them: one split of a set on disk (rendered by ``station render`` or imported by
``station import``) read through the priors core into tensors at the network input size.

Bridge: ``sim.dataset`` sample -> ``model.priors.compute_priors`` on the raw mosaic (what the camera would give)
-> stacked prior channels -> the model's region of interest -> network input size. Every frame's brightness
statistics (``model.priors.frame_stats``) come along, so a model can record what it was trained on.

Imported sets may lack object masks (the whole region of interest stands in: what a station sees) and defect masks
(``SplitTensors.mask_known`` is False for those defective parts; pixel metrics leave them out). Torch and the
renderer are imported inside the functions: the CLI imports this module to build its parser.
"""

from __future__ import annotations

import hashlib
import logging
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from station.errors import UserError

if TYPE_CHECKING:
    import numpy as np

    from model.normals.estimator import NormalEstimator
    from model.priors.frame_stats import FrameStatistics
    from station.presence import PresenceCheck

log = logging.getLogger(__name__)


@dataclass
class SplitTensors:
    """Priors at the network input size: priors (N, C, S, S), object/defect masks (N, S, S), labels (N,),
    defect type per sample ("" for good parts) and dataset indices; ``mask_known`` (N,) bool: whose defect mask is
    ground truth (good parts always; defective parts of an imported set only with a mask file);
    ``frame_stats``: each frame's ``FrameStatistics``; ``object_masks_known``: whether the set had object masks."""

    priors: Any
    object_mask: Any
    defect_mask: Any
    label: Any
    defect_type: list[str]
    index: list[int]
    mask_known: Any = None
    frame_stats: list[FrameStatistics] = field(default_factory=list)
    object_masks_known: bool = True
    unjudged: list[str | None] = field(default_factory=list)
    """Per sample: why the station would not judge its frame ("no part in view", "... % of input pixels invalid":
    ``unjudged_reason``), None when it would."""
    around: Any = None
    """(N, C, S + 2 a, S' + 2 a) the priors of the frame around each view (``model.draem.roi.around_box``; NaN
    beyond the frame), which the variation model's registration reads; None when not loaded."""


def unjudged_reason(priors: Any, n_pixels: int, presence: PresenceCheck | None = None) -> str | None:
    """Why the station would not judge a frame whose ``model.priors.Priors`` (with intensity and DoLP) these are,
    None when it would: more than ``station.decision.MAX_INVALID_FRACTION`` of its pixels invalid, or no part in
    view for ``presence`` (default: the presence check at its defaults, ``station.presence.PresenceCheck``)."""
    from station.decision import MAX_INVALID_FRACTION
    from station.presence import PresenceCheck

    invalid = (priors.n_nonfinite + priors.n_out_of_range) / n_pixels
    if invalid > MAX_INVALID_FRACTION:
        return f"{100 * invalid:.2f} % of input pixels invalid"
    return None if (presence or PresenceCheck())(priors).present else "no part in view"


def set_black_level(root: str | Path, manifest: Mapping[str, Any]) -> int:
    """The black level a set's manifest states (``black_level``: codes of the set's frames, written by ``station
    import --black-level`` or a render with a sensor pedestal), 0 when it states none. UserError naming the manifest
    and key unless it is a whole code below the set's full scale."""
    from model.priors.black_level import check_black_level

    level = manifest.get("black_level", 0)
    try:
        check_black_level(level, manifest.get("bit_depth") or 16)
    except ValueError as exc:
        raise UserError(f"{Path(root) / 'manifest.json'}: black_level: {exc}") from None
    return int(level)


def set_defect_pixels(root: str | Path, manifest: Mapping[str, Any]) -> np.ndarray | None:
    """The defect pixel map a set's manifest names (``defect_pixels``: a PNG path relative to the set, written by
    ``station import --defect-pixels``), read; None when it names none. UserError naming the manifest and key when
    it cannot be read or is not the size of the set's frames."""
    from model.priors.defect_pixels import read_defect_pixel_map

    name = manifest.get("defect_pixels")
    if not name:
        return None
    where = f"{Path(root) / 'manifest.json'}: defect_pixels"
    try:
        mask = read_defect_pixel_map(Path(root) / str(name))
    except ValueError as exc:
        raise UserError(f"{where}: {exc}") from None
    frame = (manifest.get("height"), manifest.get("width"))
    if mask.shape != frame:
        raise UserError(f"{where}: a {mask.shape[1]}x{mask.shape[0]} map for the set's {frame[1]}x{frame[0]} "
                        f"frames: a map is made for one region of interest")
    return mask


def judged_part_of(sp: SplitTensors) -> tuple[SplitTensors, dict[int, str]]:
    """The samples the station would judge, and the others' reasons by dataset index: a threshold or an
    adaptation set from frames the station logs as empty or invalid would describe no part it judges."""
    keep = [i for i, why in enumerate(sp.unjudged) if why is None]
    return subset(sp, keep), {sp.index[i]: why for i, why in enumerate(sp.unjudged) if why is not None}


def manifest_sha256(root: str | Path) -> str:
    return hashlib.sha256((Path(root) / "manifest.json").read_bytes()).hexdigest()


def frame_shape_of(root: str | Path) -> tuple[int, int] | None:
    """(height, width) px of a set's frames from its manifest; None when it does not say."""
    from sim.dataset import open_dataset

    m = open_dataset(root).manifest
    h, w = m.get("height"), m.get("width")
    ok = all(isinstance(v, int) and not isinstance(v, bool) and v > 0 for v in (w, h))
    return (h, w) if ok else None


def frame_aspect_of(root: str | Path) -> float:
    """Width / height of a set's frames from its manifest (``ModelConfig.frame_aspect``); 0 when it does not say."""
    shape = frame_shape_of(root)
    return shape[1] / shape[0] if shape else 0.0


def dome_segments_of(root: str | Path) -> tuple[float, ...]:
    """The dome segments a set's parts were imaged under, one frame each (``ModelConfig.dome_segments``); () for
    one frame per part."""
    from sim.dataset import open_dataset

    return open_dataset(root).dome_segments


def fov_of(params: dict) -> float | None:
    """A sample's horizontal field of view in degrees (rendered sets), None when unknown (imported sets)."""
    return (params.get("scene", {}).get("camera") or {}).get("fov_x_deg")


def defect_type_of(params: dict) -> str:
    return (params.get("defect") or {}).get("type", "") if params.get("label") else ""


def load_split(root: str | Path, split: str, priors: tuple[str, ...], size_px: int | tuple[int, int],
               limit: int | None = None, good_only: bool = False, progress: bool = True, roi: str = "center",
               normals: NormalEstimator | None = None, frame_aspect: float = 0.0,
               dome_segments: tuple[float, ...] = (), presence: PresenceCheck | None = None,
               around_px: int = 0) -> SplitTensors:
    """Read one split of a set into tensors at the network input size (``size_px``: (height, width) or a square's
    side), cropped to ``roi`` (see ``model.draem.config.ModelConfig.roi``) as a model trained on frames of
    ``frame_aspect`` (``ModelConfig.frame_aspect``) crops them. Object and defect masks come along (for
    anomaly synthesis and the pixel metrics) whatever the roi. The normal prior comes from ``normals`` (its field
    of view must be the set's), or from the rendered ground truth when it is None. ``dome_segments``: the model's
    (``ModelConfig.dome_segments``); the set's parts must have been imaged under the same (UserError otherwise), and
    each part's frames give one set of priors (``model.priors.api.compute_set_priors``). ``presence``: the check that
    decides which frames the station would judge (``SplitTensors.unjudged``; default: ``unjudged_reason``'s).
    ``around_px`` > 0: also the frame around each view, that many input pixels more on each side
    (``SplitTensors.around``)."""
    import numpy as np
    import torch
    from tqdm import tqdm

    from model.draem.preprocess import crop_around, crop_resize, stack_priors
    from model.draem.roi import around_box, roi_box
    from model.priors.api import compute_set_priors
    from model.priors.frame_stats import frame_statistics
    from model.priors.photometric import describe_segments
    from model.priors.sensor_correction import SensorCorrection
    from sim.dataset import open_dataset

    ds = open_dataset(root)
    if tuple(dome_segments) != ds.dome_segments:
        raise UserError(f"{root}: {describe_segments(ds.dome_segments)}, the model reads "
                        f"{describe_segments(dome_segments)}")
    idx = ds.indices(split)
    if not idx:
        raise UserError(f"{root}: no complete samples in split {split!r}")
    wanted = [p for p in priors if p != "normal"]
    names = [n for p in wanted for n in (("aolp_cos", "aolp_sin") if p == "aolp" else (p,))] or ["intensity"]
    names = list(dict.fromkeys([*names, "intensity", "dolp"]))  # the frame statistics need both
    if "normal" in priors and normals is not None:
        from model.normals.estimator import MAP_NAMES

        names = list(dict.fromkeys(names + list(MAP_NAMES)))
    layout, bit_depth = ds.manifest.get("layout", "imx250mzr"), ds.manifest.get("bit_depth")
    correction = SensorCorrection.of(set_black_level(root, ds.manifest), set_defect_pixels(root, ds.manifest))
    xs, objs, defs, labels, types, used, known, stats, unjudged, arounds = [], [], [], [], [], [], [], [], [], []
    no_object = 0
    for i in tqdm(idx, desc=f"loading {split}", unit="sample", disable=not progress):
        if limit is not None and len(used) >= limit:
            break
        s = ds.load(i)
        if good_only and s.label:
            continue
        raws = [correction(r, bit_depth) for r in s.raws]
        computed = compute_set_priors(raws, ds.dome_segments, layout, priors=names, bit_depth=bit_depth)
        maps = dict(computed)
        if "normal" in priors and normals is not None:
            fov = fov_of(s.params)
            if fov is not None and normals.fov_x_deg is not None and abs(fov - normals.fov_x_deg) > 1e-3:
                raise UserError(f"{root}: sample {i} has a {fov:.4g} deg field of view, the normal estimator reads "
                                f"{normals.fov_x_deg:.4g} deg frames; one set, one lens")
            maps["normal"] = normals.predict_frame(maps)
        elif "normal" in priors:
            if s.normal is None:
                raise UserError(f"{root}: sample {i} has no ground-truth normals (render without --no-ground-truth); "
                                f"pass --normal-net to use the learned estimator")
            maps["normal"] = s.normal
        obj_mask = s.object_mask
        if obj_mask is None:
            if roi == "object":
                raise UserError(f"{root}: sample {i} has no object mask, which roi 'object' needs (a research "
                                f"setting); models with roi 'center' read sets without object masks")
            obj_mask = np.ones(s.raw.shape, bool)  # the station's region of interest stands in
            no_object += 1
        x = stack_priors(maps, priors)
        if x.shape[1:] != obj_mask.shape:
            raise UserError(f"{root}: sample {i}: priors {x.shape[1:]} and object mask {obj_mask.shape} differ")
        defect = s.defect_mask if s.defect_mask is not None else np.zeros_like(obj_mask)
        box = roi_box(roi, obj_mask.shape, obj_mask, frame_aspect)
        xt, (obj, dm) = crop_resize(x, box, size_px, priors, (obj_mask, defect))
        xs.append(xt)
        if around_px > 0:
            arounds.append(crop_around(x, *around_box(box, xt.shape[1:], around_px), priors))
        objs.append(obj)
        defs.append(dm)
        labels.append(int(s.label))
        types.append(defect_type_of(s.params))
        used.append(i)
        known.append(not s.label or s.defect_mask is not None)
        stats.append(frame_statistics(maps, raw=raws[0], bit_depth=bit_depth))
        unjudged.append(unjudged_reason(computed, s.raw.size, presence))
    if not xs:
        raise UserError(f"{root}: split {split!r} has no usable samples")
    if no_object:
        log.info("%s: %d of %d samples without an object mask: the whole region of interest stands in",
                 root, no_object, len(used))
    return SplitTensors(torch.stack(xs), torch.stack(objs), torch.stack(defs), torch.tensor(labels), types, used,
                        torch.tensor(known, dtype=torch.bool), stats, no_object == 0, unjudged,
                        torch.stack(arounds) if arounds else None)


def check_trained_on(model: str, data: str) -> str | None:
    """The checkpoint's training-set manifest sha256 (None if unrecorded); UserError if ``data`` is another set."""
    from model.draem.checkpoint import read_sidecar

    sha = read_sidecar(model).get("data_manifest_sha256")
    if sha and sha != manifest_sha256(data):
        raise UserError(f"{model}: trained on another set than {data} (manifest sha256 {sha[:12]}...)")
    return sha


def good_part_of(sp: SplitTensors) -> SplitTensors:
    """The good samples of a split (label 0), every field alike."""
    keep = [i for i, y in enumerate(sp.label.tolist()) if y == 0]
    return subset(sp, keep)


def subset(sp: SplitTensors, keep: list[int]) -> SplitTensors:
    """The samples ``keep`` (positions) of a split: tensors indexed, per-sample lists picked."""
    import dataclasses

    import torch

    ix = torch.as_tensor(keep, dtype=torch.long)
    return dataclasses.replace(sp, **{
        f.name: (v[ix] if isinstance(v, torch.Tensor) else [v[i] for i in keep] if isinstance(v, list) else v)
        for f in dataclasses.fields(sp) for v in [getattr(sp, f.name)]})


def concat(parts: list[SplitTensors]) -> SplitTensors:
    """Several sets' splits as one, in order: tensors concatenated, per-sample lists joined (``index`` repeats
    across sets: keep each set's own where a sample must be named). ``object_masks_known`` only when every set's."""
    import dataclasses

    import torch

    if any(p.mask_known is not None for p in parts):  # a set without it: every mask known (good parts, renders)
        parts = [p if p.mask_known is not None else
                 dataclasses.replace(p, mask_known=torch.ones(len(p.index), dtype=torch.bool)) for p in parts]
    first = parts[0]
    joined = {}
    for f in dataclasses.fields(first):
        values = [getattr(p, f.name) for p in parts]
        if isinstance(values[0], torch.Tensor):  # around: only when every set has it
            joined[f.name] = torch.cat(values) if all(isinstance(v, torch.Tensor) for v in values) else None
        elif isinstance(values[0], list):
            joined[f.name] = [x for v in values for x in v]
    return dataclasses.replace(first, **joined, object_masks_known=all(p.object_masks_known for p in parts))


def rendered_defects(sp: SplitTensors, holdout_type: str | None, data: str):
    """The defective samples of a training split (without ``holdout_type``) as ``model.draem.mixed.TensorDefectData``
    for mixed supervision, and their defect types (sorted, each once); UserError when there are none."""
    from model.draem.holdout import indices_without_type
    from model.draem.mixed import TensorDefectData

    known = sp.mask_known.tolist() if sp.mask_known is not None else [True] * len(sp.index)
    defective = [i for i, y in enumerate(sp.label.tolist()) if y == 1 and known[i]]  # supervision needs the mask
    if holdout_type:
        try:
            allowed = set(indices_without_type(sp.defect_type, holdout_type).tolist())
        except ValueError as exc:
            raise UserError(f"--holdout-type {holdout_type}: {data} train split: {exc}") from None
        defective = [i for i in defective if i in allowed]
    if not defective:
        raise UserError(f"--rendered-fraction: {data} has no rendered defective parts in its train split"
                        + (f" besides {holdout_type}" if holdout_type else "")
                        + " (render it with defects in training: station render --defects-in-train)")
    d = subset(sp, defective)
    return TensorDefectData(d.priors, d.object_mask, d.defect_mask), tuple(sorted(set(d.defect_type)))
