"""The station's ``Detector`` over a ``model.draem`` checkpoint: prior maps of a frame -> score and heatmap.

Everything model-side (precision, int8 and ONNX networks, members, early exit, the normal prior, preprocessing
exactly as in training) is ``model.draem.predictor``; this adapter gives the station its ``Detector`` protocol and
its one-line ``UserError`` for a model it cannot use.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from station.errors import UserError
from station.inspector import Inference

if TYPE_CHECKING:
    import torch

    from model.draem.config import ModelConfig
    from model.draem.detector import Detector
    from model.draem.onnx_export import OnnxDetector
    from model.draem.predictor import Predictor
    from model.normals.estimator import NormalEstimator


class ModelLoadError(UserError):
    """The configured model cannot be used by the station (missing, corrupt, or unfit for a station)."""


class DraemDetector:
    """Implements ``station.inspector.Detector`` for a checkpoint folder stem (``<path>.pt`` + ``<path>.json``):
    ``model.draem.predictor.load_predictor`` with the same arguments (see there), its ``PredictorError`` raised as
    ``ModelLoadError`` with the same message (a checkpoint that cannot be read raises its ``CheckpointError``,
    itself a station user error). The predictor's attributes are read through (``members_run`` also written)."""

    def __init__(self, path: str | Path, device: str = "auto", precision: str = "auto",
                 threshold: float | None = None, early_exit_margin: float | None = None,
                 fov_x_deg: float | None = None, members: Sequence[str] | None = None,
                 around_px: int | None = None) -> None:
        from model.draem.predictor import PredictorError, load_predictor

        try:
            self.predictor: Predictor = load_predictor(path, device, precision, threshold, early_exit_margin,
                                                       fov_x_deg, members, around_px)
        except PredictorError as exc:
            raise ModelLoadError(str(exc)) from None

    def infer(self, priors: Mapping[str, np.ndarray]) -> Inference:
        """Score one frame's prior maps; the heatmap is frame-sized (zero outside the region of interest)."""
        p = self.predictor.predict(priors)
        return Inference(p.score, p.heatmap, p.checks)

    def warm_up(self, runs: int = 2) -> float:
        """Run inference on flat frames before the first part; returns the last run's milliseconds."""
        return self.predictor.warm_up(runs)

    @property
    def model_id(self) -> str:
        return self.predictor.model_id

    @property
    def threshold(self) -> float:
        """Reject when score > threshold."""
        return self.predictor.threshold

    @property
    def priors(self) -> tuple[str, ...]:
        """The ``model.priors`` maps the model reads; nothing else is computed."""
        return self.predictor.priors

    @property
    def dome_segments(self) -> tuple[float, ...]:
        """Azimuths (degrees) of the dome segments the model reads a frame of each, in order (photometric stereo,
        ``model.priors.photometric``); () for one frame per part."""
        return tuple(self.predictor.config.dome_segments)

    @property
    def used_priors(self) -> tuple[str, ...]:
        return self.predictor.used_priors

    @property
    def members(self) -> tuple[str, ...]:
        return self.predictor.members

    @property
    def members_run(self) -> int:
        """Members run so far over all parts (with early exit, fewer than parts x members)."""
        return self.predictor.members_run

    @members_run.setter
    def members_run(self, value: int) -> None:
        self.predictor.members_run = value

    @property
    def config(self) -> ModelConfig:
        return self.predictor.config

    @property
    def precision(self) -> str:
        return self.predictor.precision

    @property
    def device(self) -> torch.device:
        return self.predictor.device

    @property
    def net(self) -> Detector | OnnxDetector:
        return self.predictor.net

    @property
    def normals(self) -> NormalEstimator | None:
        return self.predictor.normals

    @property
    def early_exit_margin(self) -> float | None:
        return self.predictor.early_exit_margin

    @property
    def meta(self) -> dict[str, Any]:
        return self.predictor.meta
