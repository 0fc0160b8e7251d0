"""The station's ``Detector`` over a ``model.draem`` checkpoint: prior maps of a frame -> score and heatmap.

The frame's priors are stacked, cropped to the model's region of interest and resized exactly as in training
(``model.draem.preprocess``), so the network sees at the station what it saw in ``station train``.
"""

from __future__ import annotations

import hashlib
import logging
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from station.errors import UserError
from station.inspector import Inference

if TYPE_CHECKING:
    import torch

    from model.draem.detector import DetectorOutput
    from model.normals.estimator import NormalEstimator

log = logging.getLogger(__name__)

STATION_PRIORS = {"intensity": ("intensity",), "dolp": ("dolp",), "aolp": ("aolp_cos", "aolp_sin"),
                  "normal": ("intensity", "dolp", "aolp_cos", "aolp_sin")}
"""Model prior -> the ``model.priors`` maps it is built from ("normal": the inputs of the learned normal
estimator, ``model.normals.estimator.MAP_NAMES``; a test keeps the two equal)."""


class ModelLoadError(UserError):
    """The configured model cannot be used by the station (missing, corrupt, or unfit for a station)."""


def auto_precision(path: str | Path, device: torch.device) -> str:
    """``[model] precision = "auto"``: int8 on a CPU where ``station quantize`` made the model's int8 networks,
    found them changing at most ``AUTO_MAX_CHANGED`` of the validation decisions, and ONNX Runtime is installed
    (the fastest measured there at -0.3 to -1.2 points of image AUROC); fp32 otherwise, saying why."""
    import importlib.util

    from model.draem.quantize import fit_for_auto, int8_dir

    folder = int8_dir(path)
    if device.type != "cpu" or not (folder / "int8.json").is_file() or importlib.util.find_spec("onnxruntime") is None:
        return "fp32"
    fit, why = fit_for_auto(folder)
    if not fit:
        log.warning("%s: precision auto runs fp32, not its int8 networks: %s", path, why)
    return "int8" if fit else "fp32"


class DraemDetector:
    """Implements ``station.inspector.Detector`` for a checkpoint folder stem (``<path>.pt`` + ``<path>.json``).

    device: "auto" (CUDA when present), "cpu", "cuda"; precision: "fp32", "bf16" (autocast), "onnx" (ONNX Runtime,
    exported at load), "int8" (ONNX Runtime on the quantized networks ``station quantize`` wrote beside it) or
    "auto" (``auto_precision``: int8 on a CPU where the model has them, they passed ``station quantize``'s
    validation check and ONNX Runtime is installed, else fp32).
    ``threshold`` overrides the checkpoint's threshold (``[decision] threshold``). ``early_exit_margin``: None
    runs every member of a per-prior ensemble; 0 stops once the rest cannot change the decision (exact); m > 0
    also once the running mean is more than m from the threshold (``model.draem.early_exit``). ``fov_x_deg``:
    the lens's horizontal field of view for the normal prior's viewing directions (default: the training set's).
    ``members``: run only these members of a per-prior ensemble, and compute only their priors (the pipeline
    benchmark's prior sets; the threshold stays the whole ensemble's, so only scores and their AUROC are meant)."""

    def __init__(self, path: str | Path, device: str = "auto", precision: str = "auto",
                 threshold: float | None = None, early_exit_margin: float | None = None,
                 fov_x_deg: float | None = None, members: Sequence[str] | None = None) -> None:
        import torch

        from model.draem.checkpoint import load_checkpoint, paths
        from model.draem.errors import ModelError
        from model.draem.train import resolve_device

        if precision not in ("auto", "fp32", "bf16", "onnx", "int8"):
            raise ModelLoadError(f"[model] precision = {precision!r}: choose auto, fp32, bf16, onnx or int8")
        if Path(path).name in ("", ".", ".."):
            raise ModelLoadError(f"[model] path = {str(path)!r}: names no model (give the checkpoint's path without "
                                 f"suffix, e.g. model/weights/default)")
        pt, js = paths(path)
        if not js.is_file():
            raise ModelLoadError(f"{js}: model not found ([model] path = {str(path)!r}); train one with "
                                 f"`station train` or restore model/weights/ from git")
        try:
            self.device = resolve_device(device)
        except ModelError as exc:
            raise ModelLoadError(f"[model] device = {device!r}: {exc}") from None
        if precision == "auto":
            precision = auto_precision(path, self.device)
        ck = load_checkpoint(path, map_location=self.device)  # CheckpointError names the file
        cfg = ck.detector.config
        if cfg.roi == "object":
            raise ModelLoadError(f"{js}: model crops to roi {cfg.roi!r}, which needs ground truth at inference; "
                                 f"retrain with --roi center")
        chosen = threshold if threshold is not None else ck.threshold
        if chosen is None:
            raise ModelLoadError(f"{js}: the model has no threshold; set [decision] threshold in station.toml")
        every = tuple(cfg.networks())
        if members is not None and cfg.fusion != "ensemble":
            raise ModelLoadError(f"{js}: a fused model has no members to choose")
        if members is not None and (not members or not set(members) <= set(every)):
            raise ModelLoadError(f"{js}: members {list(members)}: name some of the ensemble's {list(every)}")
        self.members = tuple(members) if members is not None else every
        self.used_priors = tuple(p for p in cfg.priors if cfg.fusion == "fused" or p in self.members)
        """The model's priors its members read (all of them unless ``members`` leaves some out)."""
        self.normals = self._normal_estimator(js, ck.meta) if "normal" in self.used_priors else None
        if self.normals is not None and fov_x_deg is not None:
            self.normals.fov_x_deg = float(fov_x_deg)
        self.net = ck.detector.to(self.device)
        if precision == "onnx":  # ONNX Runtime on CPU, checked against torch at load
            import tempfile

            from model.draem.onnx_export import OnnxDetector

            self.device = torch.device("cpu")
            with tempfile.TemporaryDirectory() as tmp:
                self.net = OnnxDetector.from_detector(ck.detector.cpu(), tmp, torch.get_num_threads())
        elif precision == "int8":  # ONNX Runtime on CPU, networks made and checked by `station quantize`
            from model.draem.quantize import int8_dir, load_int8

            self.device = torch.device("cpu")
            try:
                self.net = load_int8(ck.detector.cpu(), int8_dir(path), ck.meta.get("weights_sha256", ""),
                                     torch.get_num_threads())
            except ModelError as exc:
                raise ModelLoadError(str(exc)) from None
        elif self.device.type == "cpu":
            self.net = self.net.to(memory_format=torch.channels_last)
        self.config = cfg
        self.threshold = float(chosen)
        self.precision = precision
        self.priors = tuple(dict.fromkeys(n for p in self.used_priors for n in STATION_PRIORS[p]))
        if early_exit_margin is not None and not 0 <= early_exit_margin <= 1:
            raise ModelLoadError(f"early exit margin {early_exit_margin} must be in [0, 1]")
        self.early_exit_margin = early_exit_margin if len(self.members) > 1 else None
        self.members_run = 0
        """Members run so far over all parts (with early exit, fewer than parts x members)."""
        sha = ck.meta.get("weights_sha256") or hashlib.sha256(pt.read_bytes()).hexdigest()
        self.model_id = f"{Path(path).name}-{cfg.preset}-{cfg.fusion}-{sha[:8]}"
        self.meta = ck.meta
        log.info("model %s: priors %s, %s %dpx, roi %s, threshold %.4g, %s %s", self.model_id, list(cfg.priors),
                 cfg.fusion, cfg.input_size_px, cfg.roi, self.threshold, self.device, precision)

    def _normal_estimator(self, js: Path, meta: Mapping) -> NormalEstimator:
        """The learned normal estimator the model was trained with (fp32 torch on the model's device, also when
        the DRAEM runs in ONNX Runtime)."""
        from model.draem.errors import ModelError
        from model.normals.estimator import load_for_checkpoint

        try:
            est = load_for_checkpoint(js, (meta.get("train") or {}).get("normal_prior"), self.device)
        except ModelError as exc:
            raise ModelLoadError(str(exc)) from None
        if est.net.config.roi != "center":
            raise ModelLoadError(f"{est.path}: normal estimator reads roi {est.net.config.roi!r}; a station needs "
                                 f"'center'")
        return est

    def infer(self, priors: Mapping[str, np.ndarray]) -> Inference:
        """Score one frame's prior maps; the heatmap is frame-sized (zero outside the region of interest)."""
        import cv2
        import torch

        from model.draem.preprocess import crop_resize, stack_priors
        from model.draem.roi import roi_box
        from model.draem.train import autocast

        shape = next(iter(priors.values())).shape[:2]
        top, left, h, w = roi_box(self.config.roi, shape)
        # stack only the square the network sees, not whole frames (the same values crop_resize would cut out)
        cut = {k: v[top:top + h, left:left + w] for k, v in priors.items()}
        if self.normals is not None:  # same square as the DRAEM's: both read roi "center" ("frame" has no normal)
            cut["normal"] = self.normals.predict_box(cut, shape, (top, left, h, w))
        x = stack_priors(cut, self.used_priors)
        xt, _ = crop_resize(x, (0, 0, h, w), self.config.input_size_px, self.used_priors)
        xt = self._all_channels(xt).unsqueeze(0).to(self.device)
        if self.device.type == "cpu" and self.precision not in ("onnx", "int8"):
            xt = xt.contiguous(memory_format=torch.channels_last)
        with autocast(self.device, self.precision):
            if self.early_exit_margin is None:
                out = self.net.predict(xt, members=self.members)
                self.members_run += len(self.members)
            else:
                out = self._predict_early(xt)
        amap = out.anomaly_map[0].float().cpu().numpy()
        heat = np.zeros(shape, np.float32)
        heat[top:top + h, left:left + w] = cv2.resize(amap, (w, h), interpolation=cv2.INTER_LINEAR)
        return Inference(float(out.score[0]), heat)

    def _all_channels(self, xt: torch.Tensor) -> torch.Tensor:
        """(C, S, S) of the priors used -> the model's full channel stack; members left out (``members``) get
        zeros they never read."""
        import torch

        from model.draem.config import PRIOR_CHANNELS, channel_slices

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

        from model.draem.detector import DetectorOutput
        from model.draem.early_exit import decided

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
            self.infer(flat)
            ms = 1e3 * (time.perf_counter() - t)
        return ms
