"""Where and how a network runs: the device and the numeric precision, for training, evaluation and the station.

``Precision`` is the one set of precision names; each user takes the ones it can run (``PRECISIONS`` for
``[model] precision`` and ``load_predictor``, ``TRAIN_PRECISIONS`` for training, ``EVAL_PRECISIONS`` for
evaluation), and the commands' ``--precision`` choices come from the same tuples. Torch is imported inside the
functions, so ``station.config`` and the commands read the names without it.
"""

from __future__ import annotations

import contextlib
from enum import StrEnum
from typing import TYPE_CHECKING

from .errors import ModelError

if TYPE_CHECKING:
    import torch


class Precision(StrEnum):
    """A network's numeric precision. Members are ``str``: configs, sidecars and reports hold the same text."""

    AUTO = "auto"
    """Training: bf16 autocast on CUDA, fp32 on CPU (``resolve_precision``). The station: int8 where the model's
    int8 networks passed ``station quantize``'s check, else fp32 (``model.draem.predictor.auto_precision``)."""
    FP32 = "fp32"
    BF16 = "bf16"
    """torch autocast to bfloat16."""
    ONNX = "onnx"
    """ONNX Runtime fp32 on CPU, exported at load."""
    INT8 = "int8"
    """ONNX Runtime on CPU, the quantized networks ``station quantize`` wrote beside the model."""


def _values(*members: Precision) -> tuple[str, ...]:
    return tuple(m.value for m in members)


PRECISIONS = _values(*Precision)
"""``[model] precision`` (``station.config``) and ``load_predictor``: every precision."""
TRAIN_PRECISIONS = _values(Precision.AUTO, Precision.FP32, Precision.BF16)
"""``station train --precision`` and ``TrainConfig.precision``."""
EVAL_PRECISIONS = _values(Precision.FP32, Precision.INT8)
"""``station eval --precision`` and ``model.draem.predictor.inference_network``."""


def resolve_device(device: str) -> torch.device:
    """"auto" (CUDA when present), "cpu", "cuda", "cuda:1", ...; ModelError for a bad name or CUDA without CUDA."""
    import torch

    if device == "auto":
        return torch.device("cuda" if torch.cuda.is_available() else "cpu")
    try:
        dev = torch.device(device)
    except RuntimeError as exc:
        raise ModelError(f"device {device!r}: {exc}") from None
    if dev.type == "cuda" and not torch.cuda.is_available():
        raise ModelError(f"device {device!r}: CUDA is not available on this machine (use \"cpu\" or \"auto\")")
    return dev


def resolve_precision(precision: str, device: torch.device) -> Precision:
    """Training's precision on ``device``: "auto" is bf16 on a CUDA device that supports it, else fp32."""
    import torch

    if precision != Precision.AUTO:
        return Precision(precision)
    return Precision.BF16 if device.type == "cuda" and torch.cuda.is_bf16_supported() else Precision.FP32


def autocast(device: torch.device, precision: str) -> contextlib.AbstractContextManager:
    """bf16: torch autocast on ``device``; anything else runs as it is (nothing to do)."""
    import torch

    if precision == Precision.BF16:
        return torch.autocast(device.type, dtype=torch.bfloat16)
    return contextlib.nullcontext()
