"""The learned normal prior as the detector uses it: prior maps of a frame -> camera-frame unit normals.

One ``NormalEstimator`` wraps a trained ``NormalUNet`` (``model.normals.net``) and the camera's horizontal field of
view, which fixes the viewing direction of each pixel (``model.normals.sfp.view_directions``). The net sees the
square its config names (``roi``, ``input_size_px``); its answer is resized back to that square (bilinear, then
renormalised) and, for a whole frame, pixels outside it face the camera (0, 0, 1).

``station train --normal-net`` computes the ``normal`` prior of every training sample with it, and the station
computes it the same way per part, so the DRAEM sees at the station the normals it was trained on.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import torch
import torch.nn.functional as F

from model.draem.preprocess import crop_resize
from model.draem.roi import roi_box
from model.draem.vectors import unit_vectors

from .errors import NormalsError
from .net import INPUT_CHANNELS, NormalUNet, load_normal_net, stack_maps
from .sfp import view_directions

MAP_NAMES = INPUT_CHANNELS[:4]
"""The prior maps (``model.priors`` names) the estimator reads: intensity, dolp, aolp_cos, aolp_sin."""
BESIDE_CHECKPOINT = "normal_net"
"""Stem (``.pt`` + ``.json``) of the estimator a DRAEM checkpoint reading the normal prior carries beside it."""


@dataclass
class NormalEstimator:
    """A trained normal net plus the field of view (degrees, horizontal; None: orthographic) of the camera whose
    frames it reads. ``path`` and ``meta`` say where it came from (the checkpoint's sidecar)."""

    net: NormalUNet
    fov_x_deg: float | None
    path: str = ""
    meta: dict[str, Any] | None = None

    @classmethod
    def load(cls, path: str | Path, fov_x_deg: float | None, device: str | torch.device = "cpu") -> NormalEstimator:
        """Load ``<path>.pt`` + ``<path>.json`` (``NormalsCheckpointError`` naming the file when unusable)."""
        net, meta = load_normal_net(path, map_location=device)
        return cls(net.to(device).eval(), fov_x_deg, str(path), meta)

    @property
    def weights_sha256(self) -> str:
        return str((self.meta or {}).get("weights_sha256", ""))

    def box(self, shape: tuple[int, int]) -> tuple[int, int, int, int]:
        """The (top, left, height, width) square of a (H, W) frame the net reads."""
        return roi_box(self.net.config.roi, shape)

    @torch.no_grad()
    def predict_box(self, maps: Mapping[str, np.ndarray], shape: tuple[int, int],
                    box: tuple[int, int, int, int] | None = None) -> np.ndarray:
        """(h, w, 3) float32 unit normals over ``box`` (default ``self.box(shape)``) of a (H, W) frame.

        ``maps``: ``MAP_NAMES`` as (h, w) arrays already cut to ``box`` (or whole frames when ``box`` is the
        frame). Non-finite inputs are read as 0 so a bad pixel cannot turn the map into NaN."""
        top, left, h, w = box if box is not None else self.box(shape)
        size = self.net.config.input_size_px
        view = view_directions(shape, self.fov_x_deg, box=(top, left, h, w), size=size)
        x4 = np.nan_to_num(stack_maps(maps), nan=0.0, posinf=0.0, neginf=0.0)
        if x4.shape[1:] != (h, w):
            raise NormalsError(f"normal estimator: maps {x4.shape[1:]} do not cover the box {(h, w)}")
        xt, _ = crop_resize(x4, (0, 0, h, w), size, ("intensity", "dolp", "aolp"))
        x = torch.cat([xt, torch.from_numpy(np.ascontiguousarray(view.transpose(2, 0, 1)))], 0)[None]
        device = next(self.net.parameters()).device
        n = self.net(x.to(device)).float()
        n = F.interpolate(n, size=(h, w), mode="bilinear", align_corners=False) if (h, w) != (size, size) else n
        n = unit_vectors(n, 1)[0]
        return n.permute(1, 2, 0).cpu().numpy().astype(np.float32, copy=False)

    def predict_frame(self, maps: Mapping[str, np.ndarray]) -> np.ndarray:
        """(H, W, 3) float32 unit normals of a whole frame (``MAP_NAMES`` as (H, W) arrays); (0, 0, 1) outside
        the net's square."""
        shape = np.shape(maps[MAP_NAMES[0]])[:2]
        top, left, h, w = self.box(shape)
        out = np.zeros((*shape, 3), np.float32)
        out[..., 2] = 1
        cut = {k: np.asarray(maps[k])[top:top + h, left:left + w] for k in MAP_NAMES}
        out[top:top + h, left:left + w] = self.predict_box(cut, shape, (top, left, h, w))
        return out


def copy_beside(src: str | Path, dst: str | Path, record: Mapping[str, Any] | None) -> None:
    """Copy the learned normal estimator that checkpoint ``src`` (a path stem or sidecar) carries beside it, as its
    ``normal_prior`` ``record`` (``describe``) names it, to ``BESIDE_CHECKPOINT`` beside checkpoint ``dst``, checked
    and written by ``copy_normal_net``: a checkpoint made from another (``station variation``, ``residual``,
    ``adapt``, ``ensemble``) loads its estimator from its own folder. Nothing for a model without a learned normal
    prior, or when both checkpoints share a folder (and so the copy)."""
    if not record or record.get("source") != "learned":
        return
    from .net import copy_normal_net

    source, target = Path(src).with_name(Path(record["file"]).stem), Path(dst).with_name(BESIDE_CHECKPOINT)
    if source.resolve() != target.resolve():
        copy_normal_net(source, target)


def describe(estimator: NormalEstimator | None, file: str = BESIDE_CHECKPOINT + ".json") -> dict[str, Any]:
    """What a DRAEM checkpoint records about its normal prior (``train.normal_prior`` in its sidecar): the
    learned estimator's sidecar ``file`` (beside the checkpoint), weights hash and field of view, or the
    rendered ground truth (``estimator`` None: a research upper bound a station cannot run)."""
    if estimator is None:
        return {"source": "ground truth"}
    return {"source": "learned", "file": file, "weights_sha256": estimator.weights_sha256,
            "fov_x_deg": estimator.fov_x_deg}


def load_for_checkpoint(sidecar: str | Path, record: Mapping[str, Any] | None,
                        device: str | torch.device = "cpu") -> NormalEstimator:
    """The learned estimator a DRAEM checkpoint (sidecar path ``sidecar``) was trained with, from its
    ``normal_prior`` record (``describe``); ``NormalsError`` naming the file when there is none or it changed."""
    js = Path(sidecar)
    if not record or record.get("source") != "learned":
        source = (record or {}).get("source", "an unknown source")
        raise NormalsError(f"{js}: the model's normal prior came from {source}, not a learned normal estimator; "
                           f"retrain with `station train --normal-net PATH`")
    path = js.with_name(str(record.get("file", "")))
    est = NormalEstimator.load(path, record.get("fov_x_deg"), device)
    if record.get("weights_sha256") and est.weights_sha256 != record["weights_sha256"]:
        raise NormalsError(f"{path}: not the normal estimator {js} was trained with (weights sha256 differs)")
    return est
