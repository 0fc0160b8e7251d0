"""Int8 post-training quantization of a detector's member networks, run by ONNX Runtime on CPU.

Static quantization in ONNX Runtime's QDQ format: weights int8 per output channel, activations uint8 with ranges
calibrated (percentile, 99.999 %) on good parts' priors, normalised exactly as at inference. The quantized
networks are an approximation: their anomaly maps differ from the fp32 ones (a few hundredths), so they are
scored like any other model (``station eval --precision int8``, ``station bench pipeline``), never assumed equal.

On disk: ``<checkpoint>.int8/<member>.onnx`` plus ``int8.json`` recording the sha256 of the checkpoint weights
they were made from, so a retrained checkpoint never runs with stale int8 networks, and ``station quantize``'s
validation check (decisions changed at the model's threshold), which ``precision = "auto"`` reads. Needs the
``onnx`` extra.
"""

from __future__ import annotations

import hashlib
import json
import tempfile
from pathlib import Path

import numpy as np
import torch

from .checkpoint import paths
from .detector import Detector
from .errors import ModelError
from .onnx_export import OnnxDetector, export_onnx

FORMAT = "polar-ano-int8"
CALIBRATION = "percentile"
"""Activation range rule: on the shipped model's test split percentile lost 0.3 points of image AUROC, min-max 1.
Min-max is the fallback where percentile cannot run (a tensor constant over the calibration set); int8.json says
which was used."""


AUTO_MAX_CHANGED = 0.05
"""``[model] precision = "auto"`` takes a model's int8 networks only where ``station quantize``'s validation check
found them changing at most this fraction of the validation parts' decisions at the model's threshold (the
all-priors ensemble's changed 15 of 40: int8 moved its scores across the threshold)."""


def read_record(js: Path) -> dict:
    """The parsed ``int8.json``; ModelError naming it when unreadable or not a JSON object."""
    try:
        meta = json.loads(js.read_text())
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        raise ModelError(f"{js}: unreadable int8 record ({exc})") from None
    if not isinstance(meta, dict):
        raise ModelError(f"{js}: not an int8 record (a JSON {type(meta).__name__}, not an object)")
    return meta


def record_check(folder: str | Path, parts: int, decisions_changed: int | None, max_score_diff: float) -> None:
    """Add the validation check of the int8 networks in ``folder`` (int8 against fp32 on ``parts`` validation
    parts; ``decisions_changed`` None when the model has no threshold) to its ``int8.json``."""
    js = Path(folder) / "int8.json"
    meta = json.loads(js.read_text())
    meta["validation"] = {"parts": parts, "decisions_changed": decisions_changed, "max_score_diff": max_score_diff}
    js.write_text(json.dumps(meta, indent=1))


def fit_for_auto(folder: str | Path) -> tuple[bool, str]:
    """Whether ``precision = "auto"`` may run the int8 networks in ``folder`` (``AUTO_MAX_CHANGED``), and why
    (or why not) in words."""
    try:
        check = read_record(Path(folder) / "int8.json").get("validation") or {}
    except ModelError as exc:
        return False, str(exc)
    if not isinstance(check, dict):
        return False, f"{Path(folder) / 'int8.json'}: validation is not an object; rerun `station quantize`"
    changed, parts = check.get("decisions_changed"), check.get("parts") or 0
    if parts < 1:
        return False, f"{Path(folder) / 'int8.json'}: no validation check of decisions; rerun `station quantize`"
    if changed is None:
        return False, "no decisions to compare (the model has no threshold: `station threshold`, then quantize)"
    verdict = changed <= AUTO_MAX_CHANGED * parts
    return verdict, (f"int8 changed {changed} of {parts} validation decisions "
                     f"({'within' if verdict else 'over'} {AUTO_MAX_CHANGED:.0%})")


def int8_dir(checkpoint: str | Path) -> Path:
    """Where the int8 networks of a checkpoint (stem, ``.pt`` or ``.json`` path) live: ``<stem>.int8/``."""
    return paths(checkpoint)[0].with_suffix(".int8")


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def quantize_detector(detector: Detector, calibration: torch.Tensor, out_dir: str | Path,
                      weights_sha256: str, provenance: dict | None = None) -> Path:
    """Write int8 copies of ``detector``'s members into ``out_dir`` (``<member>.onnx`` + ``int8.json``).

    calibration: (N, C, S, S) physical priors of good parts at the network's input size (as ``Detector.predict``
    takes them); ``weights_sha256``: of the checkpoint's weights file; ``provenance``: recorded as is (e.g. the
    calibration set). Returns ``out_dir``."""
    from onnxruntime.quantization import (
        CalibrationDataReader,
        CalibrationMethod,
        QuantFormat,
        QuantType,
        quantize_static,
    )
    from onnxruntime.quantization.shape_inference import quant_pre_process

    methods = {"percentile": CalibrationMethod.Percentile, "minmax": CalibrationMethod.MinMax}
    if calibration.ndim != 4 or calibration.shape[0] < 1:
        raise ModelError(f"calibration priors must be (N, C, S, S) with N >= 1, got {tuple(calibration.shape)}")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    z = detector.normalize(calibration.float()).numpy()

    class Reader(CalibrationDataReader):
        def __init__(self, x: np.ndarray) -> None:
            self.items = iter(x[i:i + 1] for i in range(len(x)))

        def get_next(self) -> dict | None:
            item = next(self.items, None)
            return None if item is None else {"x": item}

    members, used = {}, set()
    with tempfile.TemporaryDirectory() as tmp:
        for name, fp32 in export_onnx(detector, tmp).items():
            pre = Path(tmp) / f"{name}.pre.onnx"
            quant_pre_process(str(fp32), str(pre), skip_symbolic_shape=True)  # fixed shapes: nothing to infer
            x = np.ascontiguousarray(z[:, detector.member_slice(name)])
            for method in (CALIBRATION, "minmax"):
                try:
                    quantize_static(str(pre), str(out / f"{name}.onnx"), Reader(x), quant_format=QuantFormat.QDQ,
                                    per_channel=True, activation_type=QuantType.QUInt8, weight_type=QuantType.QInt8,
                                    calibrate_method=methods[method])
                    break
                except ValueError:  # percentile's histogram fails on a tensor constant over the calibration set
                    if method == "minmax":
                        raise
            members[name] = _sha256(out / f"{name}.onnx")
            used.add(method)
    meta = {"format": FORMAT, "version": 1, "weights_sha256": weights_sha256, "members": members,
            "calibration": {"method": "+".join(sorted(used)), "samples": int(calibration.shape[0]),
                            **(provenance or {})}}
    (out / "int8.json").write_text(json.dumps(meta, indent=1))
    return out


def load_int8(detector: Detector, folder: str | Path, weights_sha256: str, threads: int | None = None) -> OnnxDetector:
    """The int8 networks in ``folder`` as an ``OnnxDetector`` around ``detector`` (normalisation and scoring stay
    the detector's). Raises ModelError naming the file when it is missing, corrupt or made from other weights."""
    folder = Path(folder)
    js = folder / "int8.json"
    if not js.is_file():
        raise ModelError(f"{js}: no int8 networks for this model; make them with `station quantize`")
    meta = read_record(js)
    try:
        members = dict(meta["members"])
    except (ValueError, KeyError, TypeError) as exc:
        raise ModelError(f"{js}: not an int8 record (members: {exc})") from None
    if meta.get("weights_sha256") != weights_sha256:
        raise ModelError(f"{js}: made from other weights than this checkpoint's (sha256 "
                         f"{str(meta.get('weights_sha256'))[:12]} != {weights_sha256[:12]}); rerun `station quantize`")
    if set(members) != set(detector.members):
        raise ModelError(f"{js}: members {sorted(members)} != the model's {sorted(detector.members)}")
    for name, sha in members.items():
        f = folder / f"{name}.onnx"
        if not f.is_file() or _sha256(f) != sha:
            raise ModelError(f"{f}: missing or changed since `station quantize` wrote it")
    return OnnxDetector.from_files(detector, {n: folder / f"{n}.onnx" for n in members}, threads)
