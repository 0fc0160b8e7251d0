"""Soak run: the station on the virtual camera for many parts, memory and latency sampled over time, no lost rows.

Runs the configured station (``station.toml``: model, priors, queue, backpressure) on the virtual camera with the
simulated PLC for ``--parts`` parts, sampling the process's resident memory and the recent latency every
``--sample-s`` seconds. Checks at the end: log rows = parts the PLC announced (trigger-free: frames grabbed +
frames lost; every part has exactly one row), memory growth between the first and last quarter of the run,
latency drift. Writes JSON, Markdown and a plot of memory and latency against time.
"""

from __future__ import annotations

import argparse
import tempfile
import threading
import time
from pathlib import Path

from station.commands.arguments import positive_int, positive_seconds


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--config", default="station.toml")
    p.add_argument("--parts", type=positive_int, default=5000)
    p.add_argument("--sample-s", type=positive_seconds, default=2.0, help="seconds between samples")
    p.add_argument("--frame-rate-hz", type=float, default=None, help="override [camera] frame_rate_hz")


def rss_mb() -> float:
    """Resident memory of this process in MiB (Linux /proc)."""
    import os

    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2**20


def run(args: argparse.Namespace) -> int:
    import dataclasses
    from contextlib import ExitStack

    import numpy as np

    from station.assembly import build_station, load_detector, open_camera, open_link
    from station.benchmarks.report import markdown_table, write_report
    from station.config import load_config
    from station.inspection_log import InspectionLog

    cfg = load_config(args.config)
    cam = dataclasses.replace(cfg.camera, kind="sim", **({"frame_rate_hz": args.frame_rate_hz}
                                                          if args.frame_rate_hz else {}))
    cfg = dataclasses.replace(cfg, camera=cam, second_camera=dataclasses.replace(cfg.second_camera, kind="sim"))
    detector = load_detector(cfg)
    detector.warm_up()
    samples: list[dict] = []
    with tempfile.TemporaryDirectory() as tmp, ExitStack() as stack:
        log = stack.enter_context(InspectionLog(Path(tmp) / "soak.sqlite"))
        camera = open_camera(cfg)
        stack.callback(camera.close)
        link = open_link(cfg, stack, args.parts)
        station = build_station(cfg, detector, camera, link, log)
        worker = threading.Thread(target=station.run, args=(args.parts,), name="station", daemon=True)
        t0 = time.perf_counter()
        worker.start()
        while worker.is_alive():
            worker.join(args.sample_s)
            lat = list(station.stats.latencies_ms)[-200:] or [0.0]
            samples.append({"t_s": time.perf_counter() - t0, "rss_mb": rss_mb(), "rows": log.count(),
                            "p50_ms": float(np.percentile(lat, 50)), "p99_ms": float(np.percentile(lat, 99))})
            print(f"\r{samples[-1]['rows']} parts, {samples[-1]['rss_mb']:.0f} MiB, "
                  f"p99 {samples[-1]['p99_ms']:.0f} ms", end="", flush=True)
        print()
        rows = log.count()
        grabbed = station.grabbed
        # triggered: one row per part the PLC announced; free run: per frame, lost ones (id gaps) included
        lost = 0 if link.triggered else camera.statistics().dropped
        announced = link.stats_snapshot().triggers if hasattr(link, "stats_snapshot") else grabbed
        counts = dict(station.stats.counts)
    q = max(1, len(samples) // 4)
    first, last = samples[:q], samples[-q:]
    result = {
        "parts": args.parts, "rows": rows, "grabbed": grabbed, "lost_in_transport": lost, "counts": counts,
        "rows_match": rows == (announced if link.triggered else grabbed + lost) and grabbed == args.parts,
        "rss_first_quarter_mb": float(np.mean([s["rss_mb"] for s in first])),
        "rss_last_quarter_mb": float(np.mean([s["rss_mb"] for s in last])),
        "p99_first_quarter_ms": float(np.mean([s["p99_ms"] for s in first])),
        "p99_last_quarter_ms": float(np.mean([s["p99_ms"] for s in last])),
        "seconds": samples[-1]["t_s"] if samples else 0.0,
    }
    result["rss_growth_mb"] = result["rss_last_quarter_mb"] - result["rss_first_quarter_mb"]
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    _plot(out, samples)
    table = markdown_table([result], ["parts", "rows", "grabbed", "rows_match", "rss_first_quarter_mb",
                                      "rss_last_quarter_mb", "rss_growth_mb", "p99_first_quarter_ms",
                                      "p99_last_quarter_ms", "seconds"])
    write_report(out, "soak", {"result": result, "samples": samples, "config": str(args.config)}, table)
    print(table)
    return 0 if result["rows_match"] else 1


def _plot(out: Path, samples: list[dict]) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = [s["t_s"] for s in samples]
    fig, (a, b) = plt.subplots(2, 1, figsize=(6, 4.5), sharex=True)
    a.plot(t, [s["rss_mb"] for s in samples])
    a.set(ylabel="resident memory (MiB)", title="soak run")
    b.plot(t, [s["p50_ms"] for s in samples], label="p50")
    b.plot(t, [s["p99_ms"] for s in samples], label="p99")
    b.set(xlabel="seconds", ylabel="latency (ms)")
    b.legend(fontsize=7)
    fig.savefig(out / "soak.png", dpi=120, bbox_inches="tight")
    plt.close(fig)
