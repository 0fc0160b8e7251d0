"""Camera acquisition: frames/s and drop rate of the Aravis driver on Aravis's fake GigE Vision camera over
loopback (against Aravis's own arv-camera-test-0.8 on the same camera), and the virtual camera's frames/s.

The GigE Vision part runs in a private network namespace (loopback only; the project's network rule): this
module re-runs itself there as a worker (``--worker``) and reads its rows back as JSON. Each configuration gets a
fresh ``arv-fake-gv-camera-0.8 -i 127.0.0.1``, free run at the fake camera's highest rate (1000 Hz), for
``--seconds``. Drop rate = (incomplete + lost) / (delivered + incomplete + lost) frames. The fake camera and the
receiver share this machine's CPUs, so the numbers are the host's limit, not a network's.

The virtual camera replays ``--dataset`` (a ``station render`` output; a small synthetic set is written to a
temporary folder if none is given) in free run without pacing (its ceiling) and at ``--virtual-rate-hz``
(whether it keeps the pace).
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from station.benchmarks.report import markdown_table, write_report

FAKE_MAX_RATE_HZ = 1000.0


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--seconds", type=float, default=2.0, help="acquisition time per configuration")
    p.add_argument("--sizes", default="640x480,2048x2048", help="WxH list, comma-separated")
    p.add_argument("--formats", default="Mono8,Mono16", help="pixel formats, comma-separated")
    p.add_argument("--packet-sizes", default="1400,8192", help="GigE Vision packet sizes in bytes, comma-separated")
    p.add_argument("--no-peer", action="store_true", help="skip arv-camera-test-0.8")
    p.add_argument("--dataset", default="", help="rendered set for the virtual camera ('' = a synthetic one)")
    p.add_argument("--virtual-rate-hz", type=float, default=30.0, help="paced rate to check the virtual camera at")


def _configs(args: argparse.Namespace) -> list[dict[str, Any]]:
    out = []
    for size in args.sizes.split(","):
        w, h = (int(v) for v in size.lower().split("x"))
        for fmt in args.formats.split(","):
            for ps in args.packet_sizes.split(","):
                out.append({"width": w, "height": h, "pixel_format": fmt, "packet_size": int(ps)})
    return out


# -- worker: inside the namespace ---------------------------------------------------------------------------------
def _measure_driver(c: dict[str, Any], seconds: float) -> dict[str, Any]:
    from drivers.aravis_camera import AravisCamera
    from drivers.camera import CameraConfig
    from drivers.errors import CameraTimeout

    cfg = CameraConfig(device="127.0.0.1", width=c["width"], height=c["height"], pixel_format=c["pixel_format"],
                       packet_size=c["packet_size"], frame_rate_hz=FAKE_MAX_RATE_HZ, exposure_us=100.0,
                       trigger="free_run", reconnect=False, n_buffers=16, timeout_ms=1000)
    with AravisCamera(cfg) as cam:
        cam.start()
        cam.grab()  # the first frame pays for the start-up
        base = cam.statistics()
        t0 = time.perf_counter()
        n = 0
        nbytes = 0
        while time.perf_counter() - t0 < seconds:
            try:
                nbytes += cam.grab().raw.nbytes
                n += 1
            except CameraTimeout:
                pass
        elapsed = time.perf_counter() - t0
        s = cam.statistics()
    failed, dropped = s.failed - base.failed, s.dropped - base.dropped
    total = n + failed + dropped
    return {"receiver": "drivers.AravisCamera", "frames_per_s": n / elapsed, "MiB_per_s": nbytes / elapsed / 2**20,
            "delivered": n, "incomplete": failed, "lost": dropped, "drop_rate": (failed + dropped) / max(total, 1)}


def _measure_peer(c: dict[str, Any], seconds: float) -> dict[str, Any]:
    argv = ["arv-camera-test-0.8", "-n", "Aravis-Fake-BENCH", "-f", str(int(FAKE_MAX_RATE_HZ)), "-w", str(c["width"]),
            "-h", str(c["height"]), "-i", str(c["packet_size"]), "-e", "100",
            "--features", f"PixelFormat={c['pixel_format']}"]
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    time.sleep(seconds + 1.5)  # it prints a frames/s line every second
    proc.send_signal(signal.SIGINT)
    out, _ = proc.communicate(timeout=10)
    rates = [float(m) for m in re.findall(r"^\s*([\d.]+) frames/s", out, re.M)]
    stats = {k: int(v) for k, v in re.findall(r"^(n_\w+)\s+= (\d+)", out, re.M)}
    completed, failures = stats.get("n_completed_buffers", 0), stats.get("n_failures", 0)
    lost = stats.get("n_missing_frames", 0) + stats.get("n_underruns", 0)
    steady = rates[1:] or rates  # the first second includes the start-up
    fps = sum(steady) / max(len(steady), 1)
    return {"receiver": "arv-camera-test-0.8", "frames_per_s": fps,
            "MiB_per_s": fps * c["width"] * c["height"] * (2 if c["pixel_format"] == "Mono16" else 1) / 2**20,
            "delivered": completed, "incomplete": failures, "lost": lost,
            "drop_rate": (failures + lost) / max(completed + failures + lost, 1)}


def _worker(argv: list[str]) -> int:
    from drivers.netns import start_fake_gv_camera

    params = json.loads(argv[0])
    rows = []
    for c in params["configs"]:
        for measure in ([_measure_driver] if params["no_peer"] else [_measure_driver, _measure_peer]):
            fake = start_fake_gv_camera("BENCH")
            try:
                row = measure(c, params["seconds"])
            except Exception as exc:  # a failed configuration is a row, not a lost benchmark
                row = {"receiver": measure.__name__, "error": str(exc)}
            finally:
                fake.kill()
                fake.wait()
            rows.append({"camera": "fake GigE Vision (loopback)", **c, **row})
            print(json.dumps(rows[-1]), file=sys.stderr, flush=True)
    print(json.dumps(rows))
    return 0


# -- virtual camera -----------------------------------------------------------------------------------------------
def _synthetic_dataset(root: Path, n: int = 40, width: int = 640, height: int = 480) -> Path:
    import numpy as np

    from sim.dataset import DatasetSpec, Sample, init_dataset, split_of, write_sample

    init_dataset(root, DatasetSpec(width=width, height=height), n)
    rng = np.random.default_rng(0)
    for i in range(n):
        mask = np.zeros((height, width), bool)
        mask[100:120, 100:130] = i % 4 == 0
        label = int(mask.any())
        write_sample(root, Sample(i, rng.integers(0, 256, (height, width), dtype=np.uint8),
                                  {"index": i, "split": split_of(i), "label": label}, label, split_of(i),
                                  defect_mask=mask))
    return root


def _measure_virtual(dataset: str, seconds: float, rate_hz: float) -> list[dict[str, Any]]:
    from drivers.camera import CameraConfig
    from drivers.virtual_camera import VirtualCamera, VirtualCameraConfig

    rows = []
    for label, rate in (("unpaced", 1e9), (f"paced {rate_hz:g} Hz", rate_hz)):
        t_open = time.perf_counter()
        cam = VirtualCamera(CameraConfig(trigger="free_run", frame_rate_hz=rate),
                            VirtualCameraConfig(dataset, defect_rate=0.2))
        with cam:
            open_s = time.perf_counter() - t_open
            cam.start()
            t0 = time.perf_counter()
            n = 0
            while time.perf_counter() - t0 < seconds:
                f = cam.grab()
                n += 1
            elapsed = time.perf_counter() - t0
        rows.append({"camera": f"virtual ({label})", "width": f.width, "height": f.height,
                     "pixel_format": f.pixel_format, "receiver": "drivers.VirtualCamera",
                     "frames_per_s": n / elapsed, "MiB_per_s": n * f.raw.nbytes / elapsed / 2**20, "delivered": n,
                     "drop_rate": 0.0, "open_s": open_s})
    return rows


def run(args: argparse.Namespace) -> int:
    from drivers.netns import netns_command, netns_unavailable_reason

    rows: list[dict[str, Any]] = []
    notes = []
    reason = netns_unavailable_reason()
    if reason is None and shutil.which("arv-fake-gv-camera-0.8"):
        params = {"configs": _configs(args), "seconds": args.seconds,
                  "no_peer": args.no_peer or shutil.which("arv-camera-test-0.8") is None}
        cmd = netns_command(["nice", "-n", "10", sys.executable, "-m", "station.benchmarks.camera", "--worker",
                             json.dumps(params)])
        r = subprocess.run(cmd, stdout=subprocess.PIPE, text=True, cwd=Path(__file__).parents[2])
        if r.returncode != 0:
            notes.append(f"GigE Vision worker failed (exit {r.returncode})")
        else:
            rows += json.loads(r.stdout.strip().splitlines()[-1])
    else:
        notes.append(f"GigE Vision part skipped: {reason or 'arv-fake-gv-camera-0.8 not installed'}")
    with tempfile.TemporaryDirectory() as tmp:
        dataset = args.dataset or str(_synthetic_dataset(Path(tmp) / "synthetic"))
        rows += _measure_virtual(dataset, args.seconds, args.virtual_rate_hz)
    columns = ["camera", "width", "height", "pixel_format", "packet_size", "receiver", "frames_per_s", "MiB_per_s",
               "delivered", "incomplete", "lost", "drop_rate", "error"]
    title = (f"Camera acquisition, {args.seconds:g} s per configuration (fake camera free run at "
             f"{FAKE_MAX_RATE_HZ:g} Hz; sender and receiver share this machine's CPUs)\n\n")
    table = title + markdown_table(rows, columns) + "".join(f"\n{n}\n" for n in notes)
    json_path, md_path = write_report(args.out, "camera", {"benchmark": "camera", "seconds": args.seconds,
                                                           "dataset": args.dataset or "synthetic 640x480 Mono8",
                                                           "notes": notes, "rows": rows}, table)
    print(table)
    print(f"wrote {json_path} and {md_path}")
    return 0


if __name__ == "__main__" and len(sys.argv) > 2 and sys.argv[1] == "--worker":
    sys.exit(_worker(sys.argv[2:]))
