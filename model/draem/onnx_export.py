"""ONNX export of a detector and inference through ONNX Runtime, checked against the torch outputs.

Each member network is exported as ``<member>.onnx`` taking the normalised member channels (N, C, S, S) and
returning the anomaly map (N, S, S), N dynamic; normalisation and image scoring stay in numpy/torch around it,
exactly as in ``Detector.predict``. ``export_network`` is the one export of the project: the station's ONNX and
int8 paths and ``station bench model`` all go through it. Needs the ``onnx`` extra (onnx, onnxscript, onnxruntime).
"""

from __future__ import annotations

import contextlib
import hashlib
import logging
import warnings
from collections.abc import Sequence
from pathlib import Path

import torch
from torch import nn

from .detector import Detector, DetectorOutput, image_scores
from .errors import ModelError

MAX_ABS_ERROR = 1e-4
"""Largest |ONNX - torch| anomaly-map difference accepted at export (measured ~6e-8 for the fast preset)."""


class MapOnly(nn.Module):
    """Eval-mode DRAEM returning only the anomaly map (ONNX wants tensors, not dataclasses)."""

    def __init__(self, net: nn.Module) -> None:
        super().__init__()
        self.net = net

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return self.net(x).anomaly_map


BATCH_AXIS = "n"
"""Name of the one dynamic axis of every exported network: the batch, first axis of input ``x`` and output ``map``."""


def export_network(net: nn.Module, path: str | Path) -> Path:
    """Write DRAEM network ``net`` (a ``networks.Draem``: input size and channels from its ``config``) to ``path``
    as one self-contained ONNX file: input ``x`` (N, C, S, S), output ``map`` (N, S, S), N dynamic (``BATCH_AXIS``).

    Exported by torch's current exporter (``torch.export`` + onnxscript, ``dynamo=True``), not the deprecated
    TorchScript one (``dynamo=False``), after measuring both on torch 2.13 / onnxruntime 1.32 (2 shared cores,
    nice 19): the fast, lean and tiny presets export, fused and per prior, with |ONNX Runtime - torch| <= 9e-8 at
    batch 1 and 3 for either; once ONNX Runtime has optimised them both graphs hold the same operators; their int8
    (QDQ) copies give identical maps; ONNX Runtime time at batch 1, 128 px, fast fused, new / old: 0.999 and 1.004
    (medians of 200 interleaved runs each), inside the 3-7 % that two sessions of one file differ by here.

    The cost is the trace (``torch.export`` and its decompositions), ~8 s per network quiet whatever its size. So
    the graph traced before optimisation is kept per architecture (``TRACES_KEPT_BYTES``): a later network of the
    same architecture has its weights written into it, is optimised as ``torch.onnx.export(optimize=True)`` does
    (batch norms folded into the convolutions), and is checked against torch on a random batch; a graph that
    disagrees (state other than the weights) is traced afresh. On busy cores (two renders and a training): 4 s
    against 95 s for the trace, the same operators and maps (``station bench model``'s onnx and int8 rows, the
    tests)."""
    try:  # the exporter needs onnx and onnxscript (which brings onnx_ir)
        import onnx
        import onnx_ir
    except ImportError as exc:
        raise ModelError(f"ONNX export needs the onnx extra (pip install '.[onnx]'): {exc}") from None
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    net.eval()
    weights = _weights(net)
    key = hashlib.sha256(repr((type(net).__qualname__, repr(net), repr(net.config),
                               [(k, tuple(v.shape), str(v.dtype)) for k, v in weights.items()])).encode()).hexdigest()
    kept = _TRACES.pop(key, None)
    model = _filled(onnx.ModelProto.FromString(kept), weights) if kept else _trace(net)
    data = kept or model.SerializeToString()  # before the optimiser works on the graph
    program = torch.onnx.ONNXProgram(onnx_ir.from_proto(model), None)
    with _quiet("onnxscript", "onnx_ir"):
        program.optimize()
    if kept and not _agrees(program.model_proto, net):  # never trust a refilled graph that torch contradicts
        return export_network(net, path)
    _keep(key, data, model, weights)
    program.save(str(path), external_data=False)
    return path


TRACES_KEPT_BYTES = 64 * 2**20
"""Most bytes of unoptimised graphs ``export_network`` keeps, least recently used dropped first. A graph is about
its weights' size: the shipped fused network's 24 MB, a tiny one's 2 MB; a station at ``precision = "onnx"`` keeps
its networks' for its lifetime, beside their torch and ONNX Runtime copies."""

_TRACES: dict[str, bytes] = {}


def _weights(net: nn.Module) -> dict[str, torch.Tensor]:
    """Every floating-point parameter and buffer of ``net`` by its name in the exported graph (``MapOnly``'s
    ``net.`` prefix); the batch norms' step counters (integers) are not in the graph."""
    named = {**dict(net.named_parameters()), **dict(net.named_buffers())}
    return {f"net.{k}": v for k, v in named.items() if v.is_floating_point()}


def _trace(net: nn.Module):  # -> onnx.ModelProto, unoptimised, ``net``'s weights as named initializers
    x = torch.zeros(1, net.config.in_channels, *net.config.input_shape)
    with warnings.catch_warnings(), _quiet("torch.onnx", "onnxscript", "onnx_ir"):
        warnings.simplefilter("ignore")  # e.g. torch.export's own deprecations; the check against torch is ours
        return torch.onnx.export(MapOnly(net), (x,), None, input_names=["x"], output_names=["map"],
                                 dynamic_shapes={"x": {0: BATCH_AXIS}}, dynamo=True, optimize=False,
                                 verbose=False).model_proto


def _filled(model, weights: dict[str, torch.Tensor]):  # onnx.ModelProto -> the same, holding ``weights``
    from onnx import numpy_helper

    for init in model.graph.initializer:
        init.CopyFrom(numpy_helper.from_array(weights[init.name].detach().cpu().numpy(), init.name))
    return model


def _keep(key: str, data: bytes, model, weights: dict[str, torch.Tensor]) -> None:
    """Keep an unoptimised graph whose initializers are exactly ``weights`` (by name), dropping the least
    recently used beyond ``TRACES_KEPT_BYTES``."""
    if {i.name for i in model.graph.initializer} != set(weights) or len(data) > TRACES_KEPT_BYTES:
        return
    while _TRACES and sum(map(len, _TRACES.values())) + len(data) > TRACES_KEPT_BYTES:
        del _TRACES[next(iter(_TRACES))]
    _TRACES[key] = data


def _agrees(model, net: nn.Module) -> bool:
    """ONNX Runtime's map of ``model`` (a ModelProto) on a seeded random batch of 2 within ``MAX_ABS_ERROR`` of
    ``net``'s."""
    import onnxruntime as ort

    x = torch.rand(2, net.config.in_channels, *net.config.input_shape, generator=torch.Generator().manual_seed(0))
    session = ort.InferenceSession(model.SerializeToString(), session_options(1), providers=["CPUExecutionProvider"])
    with torch.no_grad():
        ref = MapOnly(net)(x).numpy()
    return float(abs(session.run(None, {"x": x.numpy()})[0] - ref).max()) <= MAX_ABS_ERROR


@contextlib.contextmanager
def _quiet(*logger_names: str):
    """Only errors from these loggers meanwhile (the exporter warns for each torchvision op it skips, its graph
    optimiser logs every pass at INFO level)."""
    loggers = [logging.getLogger(n) for n in logger_names]
    levels = [lg.level for lg in loggers]
    for lg in loggers:
        lg.setLevel(logging.ERROR)
    try:
        yield
    finally:
        for lg, level in zip(loggers, levels, strict=True):
            lg.setLevel(level)


def export_onnx(detector: Detector, out_dir: str | Path) -> dict[str, Path]:
    """Write one ``<member>.onnx`` per member into ``out_dir`` (``export_network``); returns member -> file."""
    out = Path(out_dir)
    detector.eval()
    return {name: export_network(net, out / f"{name}.onnx") for name, net in detector.members.items()}


def session_options(threads: int | None = None):  # -> onnxruntime.SessionOptions (imported lazily)
    """ONNX Runtime session options for every session of the project: ``threads`` intra-op threads (None: ORT's
    default), and idle pool threads that sleep instead of spinning: spinning took the 2 cores from the station's
    camera and decision threads (station bench pipeline, int8: p50 / p99 80 / 117 ms spinning, 59 / 77 not)."""
    import onnxruntime as ort

    options = ort.SessionOptions()
    if threads:
        options.intra_op_num_threads = threads
    options.add_session_config_entry("session.intra_op.allow_spinning", "0")
    return options


class OnnxDetector:
    """``Detector.predict`` with the member networks run by ONNX Runtime (CPU). Built by ``from_detector``
    (exports, loads and checks every member against torch on a seeded random input) or ``from_files`` (networks
    already on disk, e.g. int8 ones from ``model.draem.quantize``). Quacks like a ``Detector`` for
    ``model.draem.evaluate.evaluate`` (``eval``, ``train``, ``parameters`` are the torch detector's)."""

    def __init__(self, detector: Detector, sessions: dict[str, object]) -> None:
        self.detector, self.sessions, self.config = detector, sessions, detector.config
        self.training = False

    @classmethod
    def from_files(cls, detector: Detector, files: dict[str, Path], threads: int | None = None) -> OnnxDetector:
        try:
            import onnxruntime as ort
        except ImportError as exc:
            raise ModelError(f"ONNX Runtime inference needs the onnx extra (pip install '.[onnx]'): {exc}") from None
        options = session_options(threads)
        try:
            sessions = {k: ort.InferenceSession(str(f), options, providers=["CPUExecutionProvider"])
                        for k, f in files.items()}
        except Exception as exc:  # onnxruntime raises its own types for corrupt files
            raise ModelError(f"{list(map(str, files.values()))}: ONNX Runtime cannot load it: {exc}") from None
        return cls(detector, sessions)

    @classmethod
    def from_detector(cls, detector: Detector, work_dir: str | Path, threads: int | None = None) -> OnnxDetector:
        onnx = cls.from_files(detector, export_onnx(detector, work_dir), threads)
        x = torch.rand(1, detector.config.in_channels, *detector.config.input_shape,
                       generator=torch.Generator().manual_seed(0))
        err = float((onnx.predict(x).anomaly_map - detector.predict(x).anomaly_map).abs().max())
        if err > MAX_ABS_ERROR:
            raise ModelError(f"ONNX export of {list(onnx.sessions)} differs from torch by {err:.3g} > {MAX_ABS_ERROR}")
        return onnx

    def parameters(self):  # evaluate() reads the device from the torch detector's parameters
        return self.detector.parameters()

    def eval(self) -> OnnxDetector:
        return self

    def train(self, mode: bool = True) -> OnnxDetector:  # inference only: nothing to switch
        return self

    @torch.no_grad()
    def predict(self, x: torch.Tensor, object_mask: torch.Tensor | None = None,
                members: Sequence[str] | None = None, around: torch.Tensor | None = None) -> DetectorOutput:
        z = self.detector.normalize(x.float().contiguous())
        maps, scores = {}, {}
        for name in self.sessions if members is None else members:
            session = self.sessions[name]
            member_in = z[:, self.detector.member_slice(name)].contiguous().numpy()
            maps[name] = torch.from_numpy(session.run(None, {"x": member_in})[0]).float()
            scores[name] = image_scores(maps[name], object_mask, self.config.score_window)
        return self.detector.output(x, maps, scores, around)
