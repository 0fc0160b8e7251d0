"""The learned normal estimator: a small U-Net from polarization priors and viewing directions to unit normals,
and its checkpoint (``<name>.pt`` state_dict + ``<name>.json`` sidecar, loaded with ``weights_only=True``).

Input channels (``INPUT_CHANNELS``, physical values, no normalisation): intensity (S0/2, [0, 1]), DoLP ([0, 1]),
cos 2*AoLP, sin 2*AoLP (``model.priors.conventions``) and the viewing direction (x, y, z) of each pixel
(``model.normals.sfp.view_directions``). Output: (B, 3, H, W) unit normals in the camera frame (x image right,
y image up, z toward the camera). The network predicts a correction to the viewing direction: output =
normalize(head + view), so an untrained net answers "facing the camera" and never a zero vector.

Sidecar fields (``SIDECAR_VERSION`` 1): format "polar-ano-normals", version, convention_version, code_version,
model (``NormalNetConfig``), inputs, weights_file, weights_sha256, created, data_manifest_sha256, train, metrics.
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np
import torch
import torch.nn.functional as F
from torch import nn

from model.draem.checkpoint import code_version, load_weights, paths, read_json_sidecar, write_checkpoint_files
from model.draem.vectors import unit_vectors
from model.priors.conventions import CONVENTION_VERSION

from .errors import NormalsCheckpointError, NormalsError

INPUT_CHANNELS = ("intensity", "dolp", "aolp_cos", "aolp_sin", "view_x", "view_y", "view_z")
VIEW_SLICE = slice(4, 7)
FORMAT = "polar-ano-normals"
SIDECAR_VERSION = 1


def stack_maps(maps: Mapping[str, np.ndarray]) -> np.ndarray:
    """(4, H, W) float32 prior channels of the input (``INPUT_CHANNELS[:4]``: "intensity", "dolp", "aolp_cos",
    "aolp_sin", each (H, W), as ``model.priors.compute_priors`` returns them)."""
    try:
        chans = [np.asarray(maps[k], dtype=np.float32) for k in INPUT_CHANNELS[:4]]
    except KeyError as exc:
        raise NormalsError(f"prior maps lack {exc.args[0]!r}; the normal estimator needs "
                           f"{', '.join(INPUT_CHANNELS[:4])}; have {sorted(maps)}") from None
    shapes = {c.shape for c in chans}
    if len(shapes) != 1:
        raise NormalsError(f"normal estimator inputs differ in shape: priors {sorted(shapes)}")
    return np.stack(chans)


def stack_inputs(maps: Mapping[str, np.ndarray], view: np.ndarray) -> np.ndarray:
    """(7, H, W) float32 network input: ``stack_maps(maps)`` and (H, W, 3) viewing directions."""
    x = stack_maps(maps)
    v = np.asarray(view, dtype=np.float32)
    if v.shape != (*x.shape[1:], 3):
        raise NormalsError(f"normal estimator inputs differ in shape: priors {x.shape[1:]}, view {v.shape}")
    return np.concatenate([x, v.transpose(2, 0, 1)])


@dataclass(frozen=True)
class NormalNetConfig:
    """U-Net widths: ``base_width`` doubling over ``levels`` poolings; square input of ``input_size_px`` (a
    multiple of 2**levels) cut from the frame by ``roi`` (``model.draem.roi.roi_box``)."""

    base_width: int = 16
    levels: int = 3
    in_channels: int = len(INPUT_CHANNELS)
    input_size_px: int = 128
    roi: str = "center"

    def __post_init__(self) -> None:
        if self.base_width < 1 or self.levels < 1 or self.in_channels != len(INPUT_CHANNELS):
            raise NormalsError(f"normal net config {self}: base_width, levels >= 1 and in_channels = "
                               f"{len(INPUT_CHANNELS)} required")
        if self.input_size_px < 2**self.levels or self.input_size_px % 2**self.levels:
            raise NormalsError(f"normal net input_size_px {self.input_size_px} must be a multiple of "
                               f"{2**self.levels} (2**levels)")

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: Mapping[str, Any]) -> NormalNetConfig:
        try:
            return cls(**d)
        except TypeError as exc:
            raise NormalsError(f"normal net config: {exc}") from None


def _block(cin: int, cout: int) -> nn.Sequential:
    groups = max(1, min(8, cout // 4))
    return nn.Sequential(
        nn.Conv2d(cin, cout, 3, padding=1, bias=False), nn.GroupNorm(groups, cout), nn.ReLU(inplace=True),
        nn.Conv2d(cout, cout, 3, padding=1, bias=False), nn.GroupNorm(groups, cout), nn.ReLU(inplace=True),
    )


class NormalUNet(nn.Module):
    """U-Net (3x3 conv + GroupNorm + ReLU blocks, max-pool down, bilinear up + skip) -> unit normals."""

    def __init__(self, config: NormalNetConfig | None = None):
        super().__init__()
        self.config = config or NormalNetConfig()
        c = self.config
        widths = [c.base_width * 2**i for i in range(c.levels + 1)]
        self.down = nn.ModuleList([_block(c.in_channels, widths[0])] +
                                  [_block(widths[i - 1], widths[i]) for i in range(1, c.levels + 1)])
        self.up = nn.ModuleList([_block(widths[i + 1] + widths[i], widths[i]) for i in reversed(range(c.levels))])
        self.head = nn.Conv2d(widths[0], 3, 1)
        nn.init.zeros_(self.head.weight)
        nn.init.zeros_(self.head.bias)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        if x.ndim != 4 or x.shape[1] != self.config.in_channels:
            raise NormalsError(f"normal net input must be (B, {self.config.in_channels}, H, W), got {tuple(x.shape)}")
        skips = []
        h = x
        for i, block in enumerate(self.down):
            h = block(h if i == 0 else F.max_pool2d(h, 2))
            skips.append(h)
        for block in self.up:
            skip = skips[-2]
            skips = skips[:-1]
            h = F.interpolate(h, size=skip.shape[-2:], mode="bilinear", align_corners=False)
            h = block(torch.cat([h, skip], 1))
        return unit_vectors(self.head(h) + x[:, VIEW_SLICE], 1)


def count_parameters(net: nn.Module) -> int:
    return sum(p.numel() for p in net.parameters())


def save_normal_net(path: str | Path, net: NormalUNet, data_manifest_sha256: str | None = None,
                    train: dict[str, Any] | None = None, metrics: dict[str, Any] | None = None) -> tuple[Path, Path]:
    """Write ``<path>.pt`` (state_dict) and ``<path>.json`` (sidecar), each under a temporary name then renamed."""
    meta = {
        "format": FORMAT, "version": SIDECAR_VERSION, "convention_version": CONVENTION_VERSION,
        "code_version": code_version(), "model": net.config.to_dict(), "inputs": list(INPUT_CHANNELS),
        "output": "unit normal, camera frame: x image right, y image up, z toward the camera",
        "created": time.strftime("%Y-%m-%dT%H:%M:%S"),
        "data_manifest_sha256": data_manifest_sha256, "train": train or {}, "metrics": metrics or {},
    }
    return write_checkpoint_files(path, net, meta)


def load_normal_net(path: str | Path, map_location: str | torch.device = "cpu") -> tuple[NormalUNet, dict[str, Any]]:
    """(net in eval mode, sidecar) from ``<path>.pt`` + ``<path>.json`` (``path`` with either suffix or none).

    Raises ``NormalsCheckpointError`` naming the file when either is missing or unreadable, or when the sidecar's
    format, version, convention, inputs, hash or architecture do not match the weights or this code."""
    _, js = paths(path)
    meta = read_json_sidecar(js, NormalsCheckpointError, "normal-estimator")
    if meta.get("format") != FORMAT or meta.get("version") != SIDECAR_VERSION:
        raise NormalsCheckpointError(f"{js}: not a {FORMAT} version {SIDECAR_VERSION} sidecar "
                                     f"(format {meta.get('format')!r}, version {meta.get('version')!r})")
    if meta.get("convention_version") != CONVENTION_VERSION:
        raise NormalsCheckpointError(f"{js}: trained with polarization convention version "
                                     f"{meta.get('convention_version')}, this code uses {CONVENTION_VERSION}: retrain")
    if meta.get("inputs") != list(INPUT_CHANNELS):
        raise NormalsCheckpointError(f"{js}: inputs {meta.get('inputs')} differ from this code's "
                                     f"{list(INPUT_CHANNELS)}")
    pt = js.with_name(str(meta.get("weights_file", "")))
    state = load_weights(js, meta, map_location, error=NormalsCheckpointError)
    try:
        net = NormalUNet(NormalNetConfig.from_dict(meta.get("model") or {}))
    except NormalsError as exc:
        raise NormalsCheckpointError(f"{js}: invalid model description ({exc})") from None
    try:
        net.load_state_dict(state)
    except RuntimeError as exc:
        first = str(exc).strip().splitlines()
        raise NormalsCheckpointError(f"{pt}: weights do not match the architecture in {js} "
                                     f"({first[1].strip() if len(first) > 1 else first[0]})") from None
    return net.eval(), meta


def copy_normal_net(src: str | Path, dst: str | Path) -> tuple[Path, Path]:
    """Copy checkpoint ``src`` to ``<dst>.pt`` + ``<dst>.json`` byte for byte (same weights sha256), after checking
    that it loads; the sidecar names the new weights file."""
    import json
    import shutil

    load_normal_net(src)
    sjs, (dpt, djs) = paths(src)[1], paths(dst)
    meta = json.loads(sjs.read_text())
    dpt.parent.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(sjs.with_name(meta["weights_file"]), dpt)
    djs.write_text(json.dumps({**meta, "weights_file": dpt.name}, indent=1))
    return dpt, djs
