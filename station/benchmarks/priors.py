"""Demosaic + priors on full-resolution mosaics: frames/s and error per method, against polanalyser.

Frames are made from known Stokes images with detail (``model.priors.testing.detailed_stokes``), sampled
through the IMX250MZR mosaic and quantised to 8 and 12 bits. Errors are against those Stokes images:
S0 PSNR (peak 2, full scale), DoLP RMSE, AoLP circular RMSE in degrees where the true DoLP >= 0.1 (AoLP is
undefined at DoLP 0). ``superpixel`` (half resolution) is scored against the 2x2 means of the truth.
A 4-pixel border is left out of every error. polanalyser (the peer) runs on the same frames in the same run.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from model.priors import METHODS, compute_priors, stokes_to_mosaic
from station.benchmarks.report import markdown_table, write_report
from station.commands.arguments import even_size, positive_int

BORDER_PX = 4
AOLP_MIN_DOLP = 0.1
PRIORS = ("intensity", "dolp", "aolp")


def quantise(mosaic: np.ndarray, bits: int) -> np.ndarray:
    """Full-scale float mosaic -> raw codes of ``bits`` bits (uint8 or uint16), rounded and clipped."""
    fs = 2**bits - 1
    dtype = np.uint8 if bits <= 8 else np.uint16
    return np.clip(np.rint(mosaic * fs), 0, fs).astype(dtype)


def errors(s0: np.ndarray, dolp: np.ndarray, aolp: np.ndarray, truth: tuple[np.ndarray, ...]) -> dict[str, float]:
    """S0 PSNR (dB, peak 2), DoLP RMSE, AoLP circular RMSE (deg, true DoLP >= AOLP_MIN_DOLP); border left out."""
    t0, t1, t2 = truth
    if s0.shape != t0.shape:  # half-resolution method: compare with the 2x2 means of the truth
        t0, t1, t2 = (t.reshape(s0.shape[0], 2, s0.shape[1], 2).mean(axis=(1, 3)) for t in truth)
    b = BORDER_PX if s0.shape == truth[0].shape else BORDER_PX // 2
    crop = (slice(b, -b), slice(b, -b))
    t_dolp = np.clip(np.hypot(t1, t2) / np.maximum(t0, 1e-6), 0, 1)[crop]
    t_aolp = (0.5 * np.arctan2(t2, t1))[crop]
    mse_s0 = float(np.mean((s0[crop] - t0[crop]) ** 2))
    d_aolp = np.angle(np.exp(2j * (aolp[crop].astype(np.float64) - t_aolp))) / 2  # on the circle of period pi
    sel = t_dolp >= AOLP_MIN_DOLP
    return {
        "s0_psnr_db": 10 * np.log10(4.0 / max(mse_s0, 1e-20)),
        "dolp_rmse": float(np.sqrt(np.mean((dolp[crop] - t_dolp) ** 2))),
        "aolp_rmse_deg": float(np.degrees(np.sqrt(np.mean(d_aolp[sel] ** 2)))),
    }


def polanalyser_priors(raw: np.ndarray, full_scale: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The peer: polanalyser's bilinear demosaic, linear Stokes, DoLP and AoLP, S0 in full-scale units."""
    import polanalyser as pa

    images = pa.demosaicing(raw, pa.COLOR_PolarMono)
    stokes = pa.calcLinearStokes(images, np.deg2rad([0, 45, 90, 135]))
    return stokes[..., 0] / full_scale, pa.cvtStokesToDoLP(stokes), pa.cvtStokesToAoLP(stokes)


def median_seconds(fn: Callable[[], Any], repeats: int) -> float:
    fn()  # warm caches and allocations
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return float(np.median(times))


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--width", type=even_size, default=2448, help="mosaic width in pixels (default: IMX250MZR native)")
    p.add_argument("--height", type=even_size, default=2048)
    p.add_argument("--frames", type=positive_int, default=2, help="distinct scenes (seeds)")
    p.add_argument("--repeats", type=positive_int, default=5,
                   help="timed runs per frame and method (median is reported)")
    p.add_argument("--bits", default="8,12", help="ADC bit depths to test, comma-separated")


def run(args: argparse.Namespace) -> int:
    from model.priors.testing import detailed_stokes

    bit_depths = [int(b) for b in args.bits.split(",")]
    methods = [*METHODS, "polanalyser"]
    acc: dict[tuple[str, int], list[dict[str, float]]] = {}
    for frame in range(args.frames):
        truth = detailed_stokes(args.height, args.width, seed=frame)
        ideal = stokes_to_mosaic(*truth)
        for bits in bit_depths:
            raw = quantise(ideal, bits)
            for method in methods:
                if method == "polanalyser":
                    fn = lambda raw=raw, bits=bits: polanalyser_priors(raw, 2**bits - 1)  # noqa: E731
                else:
                    fn = lambda raw=raw, bits=bits, m=method: compute_priors(  # noqa: E731
                        raw, method=m, priors=PRIORS, bit_depth=bits)
                seconds = median_seconds(fn, args.repeats)
                out = fn()
                s0, dolp, aolp = out if method == "polanalyser" else (out["s0"], out["dolp"], out["aolp"])
                acc.setdefault((method, bits), []).append({"seconds": seconds, **errors(s0, dolp, aolp, truth)})
            if frame == 0:  # what skipping costs nothing: intensity alone needs one filter
                sec = median_seconds(lambda raw=raw, bits=bits: compute_priors(
                    raw, priors=("intensity",), bit_depth=bits), args.repeats)
                acc.setdefault(("bilinear, intensity only", bits), []).append({"seconds": sec})
    rows = []
    for (method, bits), runs in acc.items():
        row: dict[str, Any] = {"method": method, "bits": bits}
        for key in runs[0]:
            row[key] = float(np.mean([r[key] for r in runs]))
        row["ms_per_frame"] = 1e3 * row["seconds"]
        row["frames_per_s"] = 1.0 / row["seconds"]
        rows.append(row)
    for row in rows:
        peer = next(r for r in rows if r["method"] == "polanalyser" and r["bits"] == row["bits"])
        row["speedup_vs_polanalyser"] = peer["seconds"] / row["seconds"]
    columns = ["method", "bits", "ms_per_frame", "frames_per_s", "speedup_vs_polanalyser", "s0_psnr_db",
               "dolp_rmse", "aolp_rmse_deg"]
    title = (f"Priors ({', '.join(PRIORS)}) on {args.width}x{args.height} mosaics, {args.frames} scenes, "
             f"median of {args.repeats} runs\n\n")
    table = title + markdown_table(rows, columns)
    json_path, md_path = write_report(args.out, "priors", {
        "benchmark": "priors", "width": args.width, "height": args.height, "frames": args.frames,
        "repeats": args.repeats, "aolp_min_dolp": AOLP_MIN_DOLP, "border_px": BORDER_PX, "rows": rows}, table)
    print(table)
    print(f"wrote {json_path} and {md_path}")
    return 0
