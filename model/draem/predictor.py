"""A checkpoint run on one frame's prior maps: which network runs it (device, precision, int8 networks, members),
the learned normal prior it reads, early exit, warm-up. ``load_predictor`` is the one loader; the station wraps
it in its ``Detector`` (``station.model_detector``), evaluation uses ``inference_network``.

The frame's priors are stacked, cropped to the model's region of interest and resized exactly as in training
(``model.draem.preprocess``), so the network sees at inference what it saw in training. Conventions: maps are
float32 (H, W) frames keyed by ``model.priors`` names; scores and heatmap values are in [0, 1]; the heatmap is
frame-sized, zero outside the region of interest. Torch is imported inside functions, as in the rest of
``model`` where a module is read without it.
"""

from __future__ import annotations

import hashlib
import logging
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .errors import ModelError
from .runtime import PRECISIONS, Precision

if TYPE_CHECKING:
    import torch

    from model.normals.estimator import NormalEstimator

    from .checkpoint import Checkpoint
    from .config import ModelConfig
    from .detector import Detector, DetectorOutput
    from .onnx_export import OnnxDetector

log = logging.getLogger(__name__)

PRIOR_MAPS: dict[str, tuple[str, ...]] = {
    "intensity": ("intensity",), "dolp": ("dolp",), "aolp": ("aolp_cos", "aolp_sin"),
    "normal": ("intensity", "dolp", "aolp_cos", "aolp_sin"), "tilt_x": ("tilt_x",), "tilt_y": ("tilt_y",)}
"""Model prior -> the ``model.priors`` maps it is built from ("normal": the inputs of the learned normal
estimator, ``model.normals.estimator.MAP_NAMES``; a test keeps the two equal)."""

@dataclass(frozen=True)
class Prediction:
    """One frame's answer: image ``score`` in [0, 1]; ``heatmap`` (H, W) float32 in [0, 1], frame-sized, zero outside
    the region of interest; ``checks``: ``DetectorOutput.frame_checks`` of the frame, those it has (a NaN one, such
    as ``edge_bend`` without a shape check, left out; empty without them)."""

    score: float
    heatmap: np.ndarray
    checks: dict[str, float] = field(default_factory=dict)


class PredictorError(ModelError):
    """The checkpoint cannot be run as asked: a setting (``[model] path/device/precision``, members, early exit
    margin), a model unfit for inference on frames, its int8 networks or its normal estimator. The message is one
    line naming the file or the key. (A checkpoint that cannot be read raises ``CheckpointError`` instead.)"""


def auto_precision(path: str | Path, device: torch.device) -> Precision:
    """``[model] precision = "auto"``: int8 on a CPU where ``station quantize`` made the model's int8 networks,
    found them changing at most ``AUTO_MAX_CHANGED`` of the validation decisions, and ONNX Runtime is installed
    (the fastest measured there at -0.3 to -1.2 points of image AUROC); fp32 otherwise, saying why."""
    import importlib.util

    from .quantize import fit_for_auto, int8_dir

    folder = int8_dir(path)
    if device.type != "cpu" or not (folder / "int8.json").is_file() or importlib.util.find_spec("onnxruntime") is None:
        return Precision.FP32
    fit, why = fit_for_auto(folder)
    if not fit:
        log.warning("%s: precision auto runs fp32, not its int8 networks: %s", path, why)
    return Precision.INT8 if fit else Precision.FP32


def inference_network(ck: Checkpoint, path: str | Path, precision: str) -> Detector | OnnxDetector:
    """What runs checkpoint ``ck`` (loaded from ``path``) for evaluation: its torch detector ("fp32") or its int8
    networks on ONNX Runtime ("int8", made by ``station quantize``, sha256 checked). ``ModelError`` naming the
    file when the int8 networks cannot be used."""
    if precision == Precision.FP32:
        return ck.detector
    if precision != Precision.INT8:
        raise ModelError(f"precision {precision!r}: evaluation runs fp32 or int8")
    import torch

    from .quantize import int8_dir, load_int8

    return load_int8(ck.detector, int8_dir(path), ck.meta.get("weights_sha256", ""), torch.get_num_threads())


@dataclass(eq=False)
class Predictor:
    """A loaded checkpoint ready for frames (``load_predictor`` builds it). ``predict`` scores one frame;
    ``members_run`` counts the members run over all calls (with early exit, fewer than calls x members)."""

    config: ModelConfig
    net: Detector | OnnxDetector
    """The torch detector (fp32, bf16) or its ONNX Runtime networks (onnx, int8)."""
    device: torch.device
    precision: Precision
    """The precision that runs ("auto" resolved: fp32, bf16, onnx or int8)."""
    threshold: float
    """Decision threshold: reject when score > threshold (the caller's, else the checkpoint's)."""
    members: tuple[str, ...]
    """The members of a per-prior ensemble that run (all networks of the model unless chosen)."""
    used_priors: tuple[str, ...]
    """The model's priors its members read (all of them unless ``members`` leaves some out)."""
    normals: NormalEstimator | None
    """The learned normal estimator when a member reads the normal prior (fp32 torch on ``device``)."""
    early_exit_margin: float | None
    """None: every member runs; 0: stop once the rest cannot change the decision; m > 0: also once the running
    mean is more than m from the threshold (``model.draem.early_exit``). Always None for a single network and for a
    model with the variation member (its decision is not a mean of members)."""
    model_id: str
    """``<name>-<preset>-<fusion>-<first 8 hex of the weights' sha256>``."""
    meta: dict[str, Any]
    """The checkpoint's sidecar."""
    members_run: int = 0
    around_px: int = 0
    """Input pixels of the frame around the view the variation model's registration reads (the model's
    ``ModelConfig.around_px`` unless ``load_predictor`` is told otherwise; 0: none, the warp replicates the view's
    border)."""
    priors: tuple[str, ...] = field(init=False)
    """Names of the ``model.priors`` maps ``predict`` reads (from ``PRIOR_MAPS``; nothing else is needed)."""

    def __post_init__(self) -> None:
        self.priors = tuple(dict.fromkeys(n for p in self.used_priors for n in PRIOR_MAPS[p]))

    def predict(self, maps: Mapping[str, np.ndarray]) -> Prediction:
        """Score one frame's prior maps (``priors`` of them, each (H, W))."""
        import cv2
        import torch

        from .preprocess import crop_resize, stack_priors
        from .roi import around_box, roi_box
        from .runtime import autocast

        shape = next(iter(maps.values())).shape[:2]
        top, left, h, w = roi_box(self.config.roi, shape, frame_aspect=self.config.frame_aspect)
        # stack only the region the network sees, not whole frames (the same values crop_resize would cut out)
        cut = {k: v[top:top + h, left:left + w] for k, v in maps.items()}
        if self.normals is not None:
            # the estimator reads the centre square, as in training (station.datasets: predict_frame); the DRAEM's
            # region is that square or a band inside it (ModelConfig refuses roi "frame" with the normal prior)
            st, sl, sh, sw = roi_box("center", shape, frame_aspect=self.config.frame_aspect)
            square = {k: maps[k][st:st + sh, sl:sl + sw] for k in PRIOR_MAPS["normal"]}
            n = self.normals.predict_box(square, shape, (st, sl, sh, sw))
            cut["normal"] = n[top - st:top - st + h, left - sl:left - sl + w]
        x = stack_priors(cut, self.used_priors)
        xt, _ = crop_resize(x, (0, 0, h, w), self.config.input_shape, self.used_priors)
        xt = self._all_channels(xt).unsqueeze(0).to(self.device)
        around = None
        if self.around_px:
            around = self._around(maps, (top, left, h, w), around_box((top, left, h, w), self.config.input_shape,
                                                                       self.around_px))
        if self.device.type == "cpu" and self.precision not in (Precision.ONNX, Precision.INT8):
            xt = xt.contiguous(memory_format=torch.channels_last)
        with autocast(self.device, self.precision):
            if self.early_exit_margin is None:
                members = self.members if self.networks_decide else ()
                out = self.net.predict(xt, members=members, around=around)
                self.members_run += len(members)
            else:
                out = self._predict_early(xt)
        amap = out.anomaly_map[0].float().cpu().numpy()
        heat = np.zeros(shape, np.float32)
        heat[top:top + h, left:left + w] = cv2.resize(amap, (w, h), interpolation=cv2.INTER_LINEAR)
        checks = {k: float(v[0]) for k, v in out.frame_checks.items()}
        return Prediction(float(out.score[0]), heat, {k: v for k, v in checks.items() if math.isfinite(v)})

    def _around(self, maps: Mapping[str, np.ndarray], box: tuple[int, int, int, int],
                around: tuple[tuple[int, int, int, int], tuple[int, int]]) -> torch.Tensor:
        """(1, C, H + 2 a, W + 2 a) the model's priors of the frame around its view ``box`` (``around``:
        ``model.draem.roi.around_box``'s box and input shape), NaN beyond the frame, on the model's device."""
        from .preprocess import crop_around, stack_priors

        (top, left, h, w), shape = around
        t, le = max(top, 0), max(left, 0)
        near = stack_priors({k: maps[k][t:top + h, le:left + w] for k in self.priors}, self.used_priors)
        out = crop_around(near, (top - t, left - le, h, w), shape, self.used_priors)
        return self._all_channels(out).unsqueeze(0).to(self.device)

    @property
    def networks_decide(self) -> bool:
        """False when the variation model alone decides (``ModelConfig.decision``): the networks are not run, as
        their answer would change nothing the station uses (score and heatmap); ``station eval`` still runs and
        reports them."""
        return self.config.networks_decide

    def _all_channels(self, xt: torch.Tensor) -> torch.Tensor:
        """(C, S, S) of the priors used -> the model's full channel stack; members left out (``members``) get
        zeros they never read."""
        import torch

        from .config import PRIOR_CHANNELS, channel_slices

        if self.used_priors == self.config.priors:
            return xt
        full = torch.zeros((self.config.in_channels, *xt.shape[1:]), dtype=xt.dtype)
        start = 0
        for p, sl in channel_slices(self.config.priors).items():
            if p in self.used_priors:
                full[sl] = xt[start:start + PRIOR_CHANNELS[p]]
                start += PRIOR_CHANNELS[p]
        return full

    def _predict_early(self, xt: torch.Tensor) -> DetectorOutput:
        """Members one by one in the model's prior order until ``model.draem.early_exit.decided``; the output
        averages the members run."""
        import torch

        from .detector import DetectorOutput
        from .early_exit import decided

        assert self.early_exit_margin is not None
        outs = []
        for name in self.members:
            outs.append(self.net.predict(xt, members=(name,)))
            self.members_run += 1
            if decided([float(o.score[0]) for o in outs], len(self.members), self.threshold, self.early_exit_margin):
                break
        return DetectorOutput(torch.stack([o.anomaly_map for o in outs]).mean(0),
                              torch.stack([o.score for o in outs]).mean(0), {}, {})

    def warm_up(self, runs: int = 2) -> float:
        """Run inference on flat frames (first calls allocate memory and pick kernels, which would put the first
        parts over the cycle time); returns the last run's milliseconds."""
        import time

        side = 2 * self.config.input_size_px  # the network sees input_size_px whatever the frame size
        flat = {n: np.full((side, side), 1.0 if n in ("aolp_cos", "intensity") else 0.0, np.float32)
                for n in self.priors}
        ms = 0.0
        for _ in range(runs):
            t = time.perf_counter()
            self.predict(flat)
            ms = 1e3 * (time.perf_counter() - t)
        return ms


def load_predictor(path: str | Path, device: str = "auto", precision: str = "auto", threshold: float | None = None,
                   early_exit_margin: float | None = None, fov_x_deg: float | None = None,
                   members: Sequence[str] | None = None, around_px: int | None = None) -> Predictor:
    """The checkpoint at folder stem ``path`` (``<path>.pt`` + ``<path>.json``) ready for frames.

    device: "auto" (CUDA when present), "cpu", "cuda"; precision: "fp32", "bf16" (autocast), "onnx" (ONNX Runtime,
    exported at load), "int8" (ONNX Runtime on the quantized networks ``station quantize`` wrote beside it) or
    "auto" (``auto_precision``: int8 on a CPU where the model has them, they passed ``station quantize``'s
    validation check and ONNX Runtime is installed, else fp32).
    ``threshold`` overrides the checkpoint's threshold (``[decision] threshold``). ``early_exit_margin``: None
    runs every member of a per-prior ensemble; 0 stops once the rest cannot change the decision (exact); m > 0
    also once the running mean is more than m from the threshold (``model.draem.early_exit``). ``fov_x_deg``:
    the lens's horizontal field of view in degrees for the normal prior's viewing directions (default: the
    training set's). ``members``: run only these members of a per-prior ensemble, and compute only their priors
    (the pipeline benchmark's prior sets; the threshold stays the whole ensemble's, so only scores and their AUROC
    are meant). ``around_px``: input pixels of the frame around the view the variation model's registration reads
    (None: the model's, ``ModelConfig.around_px``; 0: none, as every file before 2026-12-06).

    Raises ``PredictorError`` (one line naming the file or the ``[model]`` key) for a setting or model it cannot
    run, ``CheckpointError`` for a checkpoint it cannot read.
    """
    import torch

    from .checkpoint import load_checkpoint, paths
    from .runtime import resolve_device

    if precision not in PRECISIONS:
        raise PredictorError(f"[model] precision = {precision!r}: choose auto, fp32, bf16, onnx or int8")
    if Path(path).name in ("", ".", ".."):
        raise PredictorError(f"[model] path = {str(path)!r}: names no model (give the checkpoint's path without "
                             f"suffix, e.g. model/weights/default)")
    pt, js = paths(path)
    if not js.is_file():
        raise PredictorError(f"{js}: model not found ([model] path = {str(path)!r}); train one with "
                             f"`station train` or restore model/weights/ from git")
    try:
        dev = resolve_device(device)
    except ModelError as exc:
        raise PredictorError(f"[model] device = {device!r}: {exc}") from None
    precision = auto_precision(path, dev) if precision == Precision.AUTO else Precision(precision)
    ck = load_checkpoint(path, map_location=dev)  # CheckpointError names the file
    cfg = ck.detector.config
    if cfg.roi == "object":
        raise PredictorError(f"{js}: model crops to roi {cfg.roi!r}, which needs ground truth at inference; "
                             f"retrain with --roi center")
    chosen = threshold if threshold is not None else ck.threshold
    if chosen is None:
        raise PredictorError(f"{js}: the model has no threshold; set [decision] threshold in station.toml")
    every = tuple(cfg.networks())
    if members is not None and cfg.fusion != "ensemble":
        raise PredictorError(f"{js}: a fused model has no members to choose")
    if members is not None and (not members or not set(members) <= set(every)):
        raise PredictorError(f"{js}: members {list(members)}: name some of the ensemble's {list(every)}")
    if members is not None and cfg.variation and set(members) != set(every):
        raise PredictorError(f"{js}: the model's variation member reads every prior: run all its members")
    chosen_members = tuple(members) if members is not None else every
    used_priors = tuple(p for p in cfg.priors if cfg.fusion == "fused" or p in chosen_members)
    normals = _normal_estimator(js, ck.meta, dev) if "normal" in used_priors else None
    if normals is not None and fov_x_deg is not None:
        normals.fov_x_deg = float(fov_x_deg)
    net: Detector | OnnxDetector = ck.detector.to(dev)
    if precision == Precision.ONNX:  # ONNX Runtime on CPU, checked against torch at load
        import tempfile

        from .onnx_export import OnnxDetector

        dev = torch.device("cpu")
        with tempfile.TemporaryDirectory() as tmp:
            net = OnnxDetector.from_detector(ck.detector.cpu(), tmp, torch.get_num_threads())
    elif precision == Precision.INT8:  # ONNX Runtime on CPU, networks made and checked by `station quantize`
        from .quantize import int8_dir, load_int8

        dev = torch.device("cpu")
        try:
            net = load_int8(ck.detector.cpu(), int8_dir(path), ck.meta.get("weights_sha256", ""),
                            torch.get_num_threads())
        except ModelError as exc:
            raise PredictorError(str(exc)) from None
    elif dev.type == "cpu":
        net = ck.detector.to(memory_format=torch.channels_last)  # the same module, moved above
    if early_exit_margin is not None and not 0 <= early_exit_margin <= 1:
        raise PredictorError(f"early exit margin {early_exit_margin} must be in [0, 1]")
    sha = ck.meta.get("weights_sha256") or hashlib.sha256(pt.read_bytes()).hexdigest()
    predictor = Predictor(config=cfg, net=net, device=dev, precision=precision, threshold=float(chosen),
                          members=chosen_members, used_priors=used_priors, normals=normals,
                          early_exit_margin=(early_exit_margin if len(chosen_members) > 1 and not cfg.variation
                                             else None),
                          model_id=f"{Path(path).name}-{cfg.preset}-{cfg.fusion}-{sha[:8]}", meta=ck.meta,
                          around_px=cfg.around_px if around_px is None else around_px)
    log.info("model %s: priors %s, %s %dpx, roi %s, threshold %.4g, %s %s", predictor.model_id, list(cfg.priors),
             cfg.fusion, cfg.input_size_px, cfg.roi, predictor.threshold, dev, precision)
    return predictor


def _normal_estimator(js: Path, meta: Mapping[str, Any], device: torch.device) -> NormalEstimator:
    """The learned normal estimator the model (sidecar ``js``) was trained with (fp32 torch on ``device``, the
    model's, also when the DRAEM runs in ONNX Runtime)."""
    from model.normals.estimator import load_for_checkpoint

    try:
        est = load_for_checkpoint(js, (meta.get("train") or {}).get("normal_prior"), device)
    except ModelError as exc:
        raise PredictorError(str(exc)) from None
    if est.net.config.roi != "center":
        raise PredictorError(f"{est.path}: normal estimator reads roi {est.net.config.roi!r}; a station needs "
                             f"'center'")
    return est
