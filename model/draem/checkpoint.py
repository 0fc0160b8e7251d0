"""Checkpoints: a ``state_dict`` file (``.pt``) plus a versioned JSON sidecar (``.json``) that says what the
weights mean. Loading uses ``torch.load(weights_only=True)``; nothing is unpickled.

Sidecar fields (``SIDECAR_VERSION`` 1):
    format "polar-ano-draem", version, convention_version (``model.priors.CONVENTION_VERSION``), code_version,
    model (``ModelConfig``: priors, fusion, preset, widths, input size, score window), normalization (mean, std
    per channel), threshold (image score; null until chosen) and threshold_rule, data_manifest_sha256 (of the
    training set's manifest), weights_file, weights_sha256, created, metrics (optional), train (optional state).
"""

from __future__ import annotations

import hashlib
import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import torch

from model.priors.conventions import CONVENTION_VERSION

from .config import ModelConfig
from .detector import Detector
from .errors import CheckpointError, ModelError
from .preprocess import Normalizer
from .variation import LATER_BUFFERS

NETWORKS_HALF = ("members.",)
"""Key prefixes ``save_checkpoint`` stores in float16 for a model whose networks do not decide."""

FORMAT = "polar-ano-draem"
SIDECAR_VERSION = 1


def code_version() -> str:
    """The installed package's version (``polar-ano-station``), or "unknown" when it is not installed."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("polar-ano-station")
    except PackageNotFoundError:
        return "unknown"


def sha256_file(path: str | Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


@dataclass
class Checkpoint:
    """A loaded detector and its sidecar metadata."""

    detector: Detector
    threshold: float | None
    meta: dict[str, Any] = field(default_factory=dict)


def paths(path: str | Path) -> tuple[Path, Path]:
    """(weights .pt, sidecar .json) for ``path`` given with either suffix or none."""
    p = Path(path)
    if p.name in ("", ".", ".."):
        raise CheckpointError(f"model path {str(path)!r} names no checkpoint file (give e.g. runs/train/best)")
    stem = p.with_suffix("") if p.suffix in (".pt", ".json") else p
    return stem.with_name(stem.name + ".pt"), stem.with_name(stem.name + ".json")


def write_checkpoint_files(path: str | Path, module: torch.nn.Module, meta: dict[str, Any],
                           half: tuple[str, ...] = ()) -> tuple[Path, Path]:
    """Write ``<path>.pt`` (the module's state_dict, on CPU) and ``<path>.json`` (``meta`` plus ``weights_file`` and
    ``weights_sha256``), each under a temporary name then renamed: a crash never leaves a half file under the
    final name. Shared by every checkpoint format of the project. ``half``: key prefixes whose float32 tensors are
    stored as float16 (loading copies them back into float32 parameters)."""
    pt, js = paths(path)
    pt.parent.mkdir(parents=True, exist_ok=True)
    state = {k: v.detach().cpu().contiguous() for k, v in module.state_dict().items()}
    state = {k: v.half() if v.dtype == torch.float32 and k.startswith(half) else v  # startswith(()) is False
             for k, v in state.items()}
    tmp = pt.with_name(pt.name + ".tmp")
    torch.save(state, tmp)
    tmp.replace(pt)
    meta = {**meta, "weights_file": pt.name, "weights_sha256": sha256_file(pt)}
    tmp = js.with_name(js.name + ".tmp")
    tmp.write_text(json.dumps(meta, indent=1, allow_nan=True))
    tmp.replace(js)
    return pt, js


def copy_checkpoint(src: str | Path, dst: str | Path, train: dict[str, Any] | None = None) -> tuple[Path, Path]:
    """Copy checkpoint ``src`` (stem) to ``dst`` (stem): weights, sidecar (``weights_file`` renamed; the weights'
    hash is unchanged; ``train``'s entries added to its ``train`` record, e.g. why this file was kept) and its int8
    networks (``<stem>.int8/``, which name the weights by hash) when present; each file written under a temporary
    name then renamed. Returns ``dst``'s (weights, sidecar)."""
    import shutil

    spt, sjs = paths(src)
    dpt, djs = paths(dst)
    meta = read_json_sidecar(sjs)
    if not spt.is_file():
        raise CheckpointError(f"{spt}: weights missing")
    dpt.parent.mkdir(parents=True, exist_ok=True)
    tmp = dpt.with_name(dpt.name + ".tmp")
    shutil.copyfile(spt, tmp)
    tmp.replace(dpt)
    tmp = djs.with_name(djs.name + ".tmp")
    if train:
        meta = {**meta, "train": {**meta.get("train", {}), **train}}
    tmp.write_text(json.dumps({**meta, "weights_file": dpt.name}, indent=1, allow_nan=True))
    tmp.replace(djs)
    sint8, dint8 = spt.with_suffix(".int8"), dpt.with_suffix(".int8")
    if dint8.exists():
        shutil.rmtree(dint8)  # int8 networks of the replaced weights would be refused by hash anyway
    if sint8.is_dir():
        shutil.copytree(sint8, dint8)
    return dpt, djs


def read_json_sidecar(js: Path, error: type[CheckpointError] = CheckpointError, what: str = "checkpoint"
                      ) -> dict[str, Any]:
    """The parsed sidecar ``js`` of a ``what`` checkpoint; ``error`` naming it when missing or unreadable."""
    if not js.is_file():
        raise error(f"{js}: {what} sidecar missing")
    try:
        meta = json.loads(js.read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise error(f"{js}: unreadable sidecar ({exc})") from None
    if not isinstance(meta, dict):
        raise error(f"{js}: not a JSON object (a {type(meta).__name__}); not a {what} sidecar")
    weights = meta.get("weights_file")
    if weights is not None and not is_plain_file_name(weights):
        raise error(f"{js}: weights_file = {weights!r}: must be a file name in the sidecar's folder (no path)")
    return meta


def is_plain_file_name(name: object) -> bool:
    """Whether ``name`` is a bare file name (no folder part, not "." or ".."): what a sidecar may point to."""
    return isinstance(name, str) and name not in ("", ".", "..") and "/" not in name and "\\" not in name


def finite_number(value: object) -> bool:
    """A real number (not a bool, not a string) that is finite."""
    return isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)


def check_decision_numbers(js: Path, meta: dict[str, Any]) -> None:
    """Every number of a sidecar that reaches a decision, checked where it is loaded: ``threshold`` null or finite in
    [0, 1] (image scores are probabilities), ``normalization`` mean and std lists of finite numbers with std > 0.
    CheckpointError naming the file and key otherwise (a NaN threshold would pass every part)."""
    t = meta.get("threshold")
    if t is not None and not (finite_number(t) and 0.0 <= t <= 1.0):
        raise CheckpointError(f"{js}: threshold = {t!r}: must be a finite number in [0, 1] (or null until chosen)")
    norm = meta.get("normalization")
    if not isinstance(norm, dict):
        raise CheckpointError(f"{js}: normalization = {norm!r}: must be an object with mean and std lists")
    for key in ("mean", "std"):
        v = norm.get(key)
        if not isinstance(v, list) or not v or not all(finite_number(x) for x in v):
            raise CheckpointError(f"{js}: normalization.{key} = {v!r}: must be a list of finite numbers")
    if not all(x > 0 for x in norm["std"]):
        raise CheckpointError(f"{js}: normalization.std = {norm['std']!r}: every std must be > 0")
    if len(norm["mean"]) != len(norm["std"]):
        raise CheckpointError(f"{js}: normalization: {len(norm['mean'])} means for {len(norm['std'])} stds")


def load_weights(js: Path, meta: dict[str, Any], map_location: str | torch.device = "cpu", verify_hash: bool = True,
                 error: type[CheckpointError] = CheckpointError) -> dict[str, torch.Tensor]:
    """The state_dict named by sidecar ``js`` (``meta["weights_file"]``), loaded with ``weights_only=True`` after
    checking its sha256; ``error`` naming the file when missing, replaced, corrupt or not a state_dict."""
    pt = js.with_name(str(meta.get("weights_file") or ""))
    if not meta.get("weights_file") or not pt.is_file():
        raise error(f"{pt}: weights file missing (named in {js})")
    if verify_hash and meta.get("weights_sha256") and sha256_file(pt) != meta["weights_sha256"]:
        raise error(f"{pt}: weights do not match the sha256 in {js} (file replaced or corrupt)")
    try:
        state = torch.load(pt, map_location=map_location, weights_only=True)
    except Exception as exc:  # torch raises several types for corrupt or pickled files
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else ""  # torch's explanation runs 6 lines
        raise error(f"{pt}: cannot load weights safely ({type(exc).__name__}: {first})") from None
    if not isinstance(state, dict):
        raise error(f"{pt}: not a state_dict")
    return state


def save_checkpoint(path: str | Path, detector: Detector, threshold: float | None = None, threshold_rule: str = "",
                    data_manifest_sha256: str | None = None, metrics: dict[str, Any] | None = None,
                    train: dict[str, Any] | None = None) -> tuple[Path, Path]:
    """Write ``<path>.pt`` (state_dict) and ``<path>.json`` atomically (``write_checkpoint_files``). A model whose
    networks do not decide (``decision`` "variation" or "residual") stores its DRAEM networks in float16
    (``NETWORKS_HALF``): float32 would double the file for nothing (the shipped one: 24.4 MB of
    networks in float32); they load back into float32."""
    n = detector.normalizer
    meta = {
        "format": FORMAT, "version": SIDECAR_VERSION, "convention_version": CONVENTION_VERSION,
        "code_version": code_version(), "model": detector.config.to_dict(),
        "normalization": {"mean": list(n.mean), "std": list(n.std)},
        "threshold": threshold, "threshold_rule": threshold_rule, "data_manifest_sha256": data_manifest_sha256,
        "created": time.strftime("%Y-%m-%dT%H:%M:%S"), "metrics": metrics or {}, "train": train or {},
    }
    half = () if detector.config.networks_decide else NETWORKS_HALF
    return write_checkpoint_files(path, detector, meta, half)


def read_sidecar(path: str | Path) -> dict[str, Any]:
    """The sidecar of checkpoint ``path``, checked for format, version and convention version."""
    _, js = paths(path)
    meta = read_json_sidecar(js)
    if meta.get("format") != FORMAT:
        raise CheckpointError(f"{js}: not a {FORMAT} sidecar (format {meta.get('format')!r})")
    if meta.get("version") != SIDECAR_VERSION:
        raise CheckpointError(f"{js}: sidecar version {meta.get('version')}, this code reads {SIDECAR_VERSION}")
    if meta.get("convention_version") != CONVENTION_VERSION:
        raise CheckpointError(f"{js}: trained with polarization convention version {meta.get('convention_version')}, "
                              f"this code uses {CONVENTION_VERSION}: retrain")
    for key in ("model", "normalization", "weights_file"):
        if key not in meta:
            raise CheckpointError(f"{js}: sidecar lacks {key!r}")
    check_decision_numbers(js, meta)
    return meta


def load_checkpoint(path: str | Path, map_location: str | torch.device = "cpu", expect_priors: tuple[str, ...] | None
                    = None, verify_hash: bool = True) -> Checkpoint:
    """Load a detector (eval mode) from ``<path>.pt`` + ``<path>.json``.

    Raises CheckpointError naming the file when either is missing or unreadable, when the weights' hash, keys or
    shapes do not match the sidecar, or when ``expect_priors`` differs from the model's priors."""
    meta = read_sidecar(path)
    _, js = paths(path)
    pt = js.with_name(meta["weights_file"])
    state = load_weights(js, meta, map_location, verify_hash)
    try:
        config = ModelConfig.from_dict(meta["model"])
        norm = Normalizer(tuple(meta["normalization"]["mean"]), tuple(meta["normalization"]["std"]))
        detector = Detector(config, norm)
    except (ModelError, KeyError, TypeError, AttributeError) as exc:
        raise CheckpointError(f"{js}: invalid model description ({exc})") from None
    if len(norm.mean) != config.in_channels:
        raise CheckpointError(f"{js}: normalization has {len(norm.mean)} channels, the model reads "
                              f"{config.in_channels}")
    if expect_priors is not None and tuple(expect_priors) != config.priors:
        raise CheckpointError(f"{js}: model uses priors {list(config.priors)}, expected {list(expect_priors)}")
    if detector.variation is not None:  # added later: absent, they score as their models did (LATER_BUFFERS)
        for name in LATER_BUFFERS:
            state.setdefault(f"variation.{name}", detector.variation.get_buffer(name).clone())
        try:
            detector.variation.size_fitted(state, "variation.")  # their size is the fit's
        except ModelError as exc:
            raise CheckpointError(f"{pt}: {exc}") from None
    if detector.residual is not None:  # added later (rule 49): absent, the networks are no second look
        state.setdefault("residual.look", detector.residual.look.clone())
        state.setdefault("residual.blend", detector.residual.blend.clone())  # added later: absent, the cascade
    missing = sorted(set(detector.state_dict()) - set(state))
    unexpected = sorted(set(state) - set(detector.state_dict()))
    if missing or unexpected:
        raise CheckpointError(f"{pt}: weights do not match the architecture in {js}: missing {missing[:3]}"
                              f"{'...' if len(missing) > 3 else ''}, unexpected {unexpected[:3]}"
                              f"{'...' if len(unexpected) > 3 else ''}")
    for k, v in detector.state_dict().items():
        if state[k].shape != v.shape:
            raise CheckpointError(f"{pt}: {k} has shape {tuple(state[k].shape)}, the architecture in {js} wants "
                                  f"{tuple(v.shape)}")
    detector.load_state_dict(state)
    detector.eval()
    for part in (detector.variation, detector.residual):
        if part is not None:
            try:
                part.check()
            except ModelError as exc:
                raise CheckpointError(f"{pt}: {exc}") from None
    return Checkpoint(detector, meta.get("threshold"), meta)
