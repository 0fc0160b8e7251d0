"""DRAEM inference latency per preset x input size x precision (fp32, bf16, ONNX Runtime fp32 and int8) x fusion,
on this machine.

Latency is per part (one image through every member: 4 priors = 4 networks for the ensemble, 1 for the fused
network), warm, batch 1, median of ``--repeats``; the published DRAEM size (``paper`` preset, one network,
256 px, fp32) is the baseline ratio. The ONNX rows run the networks exported as the station exports them
(``model.draem.onnx_export.export_network``). The int8 rows quantize the random-weight networks as ``station quantize``
does, calibrated on random inputs: their time is a trained model's, their error against fp32 is not. A model with
the normal prior also runs the learned normal estimator once per part (row "normal-net", ``model.normals``, fp32
torch at the station): add its time to the model's. Accuracy per configuration needs trained checkpoints: see
``station eval`` and ``station bench pipeline``.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

from station.commands.arguments import positive_int

PRIORS = ("intensity", "dolp", "aolp", "normal")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--presets", default="fast,tiny")
    p.add_argument("--sizes", default="", help="comma-separated input sizes (default: each preset's own)")
    p.add_argument("--precisions", default="fp32,bf16,onnx,int8",
                   help="fp32, bf16 (CPU autocast), onnx (ONNX Runtime fp32), int8 (ONNX Runtime, quantized as "
                        "station quantize does)")
    p.add_argument("--fusions", default="ensemble,fused")
    p.add_argument("--repeats", type=positive_int, default=5)
    p.add_argument("--threads", type=int, default=2, help="torch / ONNX Runtime intra-op threads")
    p.add_argument("--no-baseline", action="store_true", help="skip the paper-size baseline (~3 s per run on CPU)")
    p.add_argument("--max-seconds", type=float, default=20.0,
                   help="skip repeats once one run of a configuration takes longer than this")


def _time(fn, repeats: int, max_seconds: float) -> tuple[float, int]:
    fn()  # warm-up
    ts = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t)
        if ts[-1] > max_seconds:
            break
    return statistics.median(ts) * 1e3, len(ts)


def _measure(preset: str, size: int, precision: str, fusion: str, args) -> dict:
    import torch

    from model.draem.config import ModelConfig
    from model.draem.detector import Detector
    from model.draem.networks import count_parameters

    priors = ("intensity",) if fusion == "baseline" else PRIORS
    cfg = ModelConfig.from_preset(preset, priors, "fused" if fusion == "baseline" else fusion, size)
    det = Detector(cfg).eval()
    if fusion == "baseline":  # the published network: 3 input channels
        from model.draem.config import NetworkConfig
        from model.draem.networks import Draem
        nets = {"rgb": Draem(NetworkConfig(3, 128, 64, size)).eval()}
    else:
        nets = dict(det.members.items())
    params = sum(count_parameters(n) for n in nets.values())
    inputs = {k: torch.randn(1, n.config.in_channels, size, size) for k, n in nets.items()}
    row = {"preset": preset, "size": size, "precision": precision, "fusion": fusion, "networks": len(nets),
           "params_M": params / 1e6}
    if precision in ("onnx", "int8"):
        import onnxruntime as ort

        from model.draem.onnx_export import export_network, session_options
        from model.draem.quantize import quantize_detector

        sessions, max_err = {}, 0.0
        with tempfile.TemporaryDirectory() as d:
            if precision == "int8":  # the detector's own members, calibrated on 8 random inputs
                quantize_detector(det, torch.randn(8, cfg.in_channels, size, size), d, "random weights")
            for k, n in nets.items():
                f = Path(d) / f"{k}.onnx"
                if precision == "onnx":  # the station's export (model.draem.onnx_export), as int8's above
                    export_network(n, f)
                sessions[k] = ort.InferenceSession(str(f), session_options(args.threads),
                                                   providers=["CPUExecutionProvider"])
                with torch.no_grad():
                    ref = n(inputs[k]).anomaly_map.numpy()
                got = sessions[k].run(None, {"x": inputs[k].numpy()})
                max_err = max(max_err, float(abs(got[0] - ref).max()))
            feeds = {k: {"x": v.numpy()} for k, v in inputs.items()}
            ms, reps = _time(lambda: [s.run(None, feeds[k]) for k, s in sessions.items()], args.repeats,
                             args.max_seconds)
        row["onnx_max_abs_err"] = max_err
    else:
        for k, n in nets.items():
            n.to(memory_format=torch.channels_last)
            inputs[k] = inputs[k].contiguous(memory_format=torch.channels_last)

        def run():
            with torch.no_grad(), torch.autocast("cpu", dtype=torch.bfloat16, enabled=precision == "bf16"):
                for k, n in nets.items():
                    n(inputs[k])

        ms, reps = _time(run, args.repeats, args.max_seconds)
    row.update(ms_per_part=ms, runs=reps)
    return row


def _measure_normal_net(args) -> dict:
    """The learned normal estimator's default architecture (``NormalNetConfig``), fp32, batch 1."""
    import torch

    from model.normals.net import NormalNetConfig, NormalUNet, count_parameters

    net = NormalUNet(NormalNetConfig()).eval()
    x = torch.randn(1, net.config.in_channels, net.config.input_size_px, net.config.input_size_px)

    def run():
        with torch.no_grad():
            net(x)

    ms, reps = _time(run, args.repeats, args.max_seconds)
    return {"preset": "normal-net", "size": net.config.input_size_px, "precision": "fp32", "fusion": "-",
            "networks": 1, "params_M": count_parameters(net) / 1e6, "ms_per_part": ms, "runs": reps}


def run(args: argparse.Namespace) -> int:
    import torch

    from model.draem.config import PRESETS
    from station.benchmarks.report import markdown_table, write_report

    torch.set_num_threads(args.threads)
    rows = []
    if not args.no_baseline:
        rows.append(_measure("paper", 256, "fp32", "baseline", args))
        print(rows[-1], flush=True)
    for preset in args.presets.split(","):
        sizes = [int(s) for s in args.sizes.split(",") if s] or [PRESETS[preset].input_size_px]
        for size in sizes:
            for fusion in args.fusions.split(","):
                for precision in args.precisions.split(","):
                    rows.append(_measure(preset, size, precision, fusion, args))
                    print(rows[-1], flush=True)
    rows.append(_measure_normal_net(args))  # PRIORS include the normal prior
    print(rows[-1], flush=True)
    base = rows[0]["ms_per_part"] if not args.no_baseline else None
    for r in rows:
        r["speedup_vs_paper"] = base / r["ms_per_part"] if base else float("nan")
    cols = ["preset", "size", "fusion", "precision", "networks", "params_M", "ms_per_part", "speedup_vs_paper",
            "onnx_max_abs_err", "runs"]
    table = markdown_table(rows, cols)
    write_report(args.out, "model", {"rows": rows, "threads": args.threads, "priors": list(PRIORS),
                                     "torch": torch.__version__}, table)
    print(table)
    return 0
