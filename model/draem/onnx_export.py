"""ONNX export of a detector and inference through ONNX Runtime, checked against the torch outputs.

Each member network is exported as ``<member>.onnx`` taking the normalised member channels (1, C, S, S) and
returning the anomaly map (1, S, S); normalisation and image scoring stay in numpy/torch around it, exactly as in
``Detector.predict``. Needs the ``onnx`` extra (onnx, onnxruntime).
"""

from __future__ import annotations

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


def export_onnx(detector: Detector, out_dir: str | Path) -> dict[str, Path]:
    """Write one ``<member>.onnx`` per member into ``out_dir``; returns member -> file."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    detector.eval()
    size = detector.config.input_size_px
    files = {}
    for name, net in detector.members.items():
        sl = detector.member_slice(name)
        x = torch.zeros(1, sl.stop - sl.start, size, size)
        files[name] = out / f"{name}.onnx"
        with warnings.catch_warnings():  # shape checks in forward() become constants: the size is fixed anyway
            warnings.simplefilter("ignore", torch.jit.TracerWarning)
            torch.onnx.export(MapOnly(net), (x,), str(files[name]), input_names=["x"], output_names=["map"],
                              dynamic_axes={"x": {0: "n"}, "map": {0: "n"}}, dynamo=False)
        net.eval()  # the exporter may leave the module in train mode
    return files


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
    ``model.draem.train.evaluate`` (``eval``, ``train``, ``parameters`` are the torch detector's)."""

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
        x = torch.rand(1, detector.config.in_channels, detector.config.input_size_px, detector.config.input_size_px,
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
                members: Sequence[str] | None = None) -> DetectorOutput:
        z = self.detector.normalize(x.float().contiguous())
        maps, scores = {}, {}
        for name in self.sessions if members is None else members:
            session = self.sessions[name]
            member_in = z[:, self.detector.member_slice(name)].contiguous().numpy()
            maps[name] = torch.from_numpy(session.run(None, {"x": member_in})[0]).float()
            scores[name] = image_scores(maps[name], object_mask, self.config.score_window)
        amap = torch.stack(list(maps.values())).mean(0)
        return DetectorOutput(amap, torch.stack(list(scores.values())).mean(0), maps, scores)
