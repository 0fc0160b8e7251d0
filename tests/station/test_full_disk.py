"""A real full disk: the inspection log on a 600 KiB tmpfs in a private mount namespace. The PLC hears no decision
whose row is not durable, the station keeps answering (rejects) while the disk is full, and every row is written
once space returns. (On the same disk the station used to stop: 44 decisions at the PLC, 43 rows.)"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

SCRIPT = textwrap.dedent('''
    import json, sys, threading, time
    from collections import deque
    from pathlib import Path
    import numpy as np
    from drivers.camera import CameraBase, CameraConfig
    from drivers.errors import CameraTimeout
    from drivers.frame import Frame
    from drivers.line_io import Trigger
    from model.priors import IMX250MZR
    from station.inspection_log import InspectionLog
    from station.inspector import Inference, Inspector
    from station.line_link import NoLink
    from station.loop import Station

    disk = Path(sys.argv[1])
    N = 400

    class Camera(CameraBase):
        def __init__(self):
            super().__init__(CameraConfig(trigger="software"))
            self.n = 0
        def open(self): ...
        def close(self): ...
        def start(self): ...
        def stop(self): ...
        def configure(self, config): ...
        def trigger(self): ...
        def grab(self, timeout_ms=None):
            self.n += 1
            return Frame(np.full((8, 8), 20, np.uint8), "Mono8", 8, self.n, 0, time.time_ns())

    class Detector:
        model_id, threshold, priors = "test", 0.5, ("intensity",)
        def infer(self, priors):
            return Inference(0.1)

    class PLC(NoLink):
        triggered, has_plc = True, True
        def __init__(self, log):
            now = time.perf_counter()
            self.pending = deque(Trigger(f"T{i}", now) for i in range(N))
            self.log, self.decisions, self.without_row = log, {}, 0
            self._out = []
        def next_trigger(self, timeout_s):
            if not self.pending:
                return None
            t = self.pending.popleft()
            return Trigger(t.part_id, time.perf_counter())
        def report(self, part_id, decision, reason, deadline=None):
            recent = self.log.rows(after_id=self.log.last_id() - 50)
            if decision == "pass" and not any(r["part_id"] == part_id for r in recent):
                self.without_row += 1  # the PLC passes a part the log does not hold
            self.decisions[part_id] = decision
            self._out.append((part_id, True, time.perf_counter(), decision))
            if len(self.decisions) == int(0.75 * N):
                (disk / "filler").unlink()  # space returns
            return False
        def outcomes(self):
            out, self._out = self._out, []
            return out

    log = InspectionLog(disk / "log.sqlite")
    with open(disk / "filler", "wb", buffering=0) as f:  # the disk fills but for ~40 KiB
        try:
            while True:
                f.write(b"x" * 4096)
        except OSError:
            pass
    size = (disk / "filler").stat().st_size
    with open(disk / "filler", "r+b") as f:
        f.truncate(size - 40 * 1024)
    plc = PLC(log)
    station = Station(Camera(), Inspector(Detector(), IMX250MZR), plc, log, threshold=0.5, cycle_time_ms=10_000.0,
                      queue_size=8, backpressure="block")
    station.run(max_parts=N)
    rows = list(InspectionLog(disk / "log.sqlite", readonly=True).rows())
    rejected = sorted(p for p, d in plc.decisions.items() if d == "reject")
    print(json.dumps({"decisions": len(plc.decisions), "rows": len(rows), "rejected": len(rejected),
                      "unique": len({r["part_id"] for r in rows}), "unrecorded": station.unrecorded_rows,
                      "not_recorded": sum("not recorded" in (r["reason"] or "") for r in rows),
                      "delivered": sum(bool(r["io_delivered"]) for r in rows), "without_row": plc.without_row}))
''')


def test_full_disk_in_a_private_mount_namespace(tmp_path: Path) -> None:
    if shutil.which("unshare") is None or os.geteuid() != 0:
        pytest.skip("needs root and unshare for a private mount namespace with a tmpfs")
    probe = subprocess.run(["unshare", "-m", "sh", "-c", f"mount -t tmpfs -o size=64k tmpfs {tmp_path}"],
                           capture_output=True, text=True)
    if probe.returncode != 0:
        pytest.skip(f"unshare -m not permitted here: {probe.stderr.strip()}")
    disk = tmp_path / "disk"
    disk.mkdir()
    script = tmp_path / "run.py"
    script.write_text(SCRIPT)
    r = subprocess.run(["unshare", "-m", "sh", "-c", f"mount --make-rprivate / && mount -t tmpfs -o size=600k tmpfs "
                        f"{disk} && exec {sys.executable} {script} {disk}"], capture_output=True, text=True,
                       timeout=300, cwd=Path(__file__).parents[2])
    assert r.returncode == 0, r.stderr[-3000:]
    got = json.loads(r.stdout.strip().splitlines()[-1])
    assert got["decisions"] == 400  # the station kept answering through the full disk
    assert got["rows"] == got["unique"] == 400 and got["unrecorded"] == 0  # written once space returned
    assert got["rejected"] > 0 and got["not_recorded"] == got["rejected"]  # only parts whose row failed
    assert got["delivered"] == 400  # the PLC's ACKs reached the rows, the late ones included
    assert got["without_row"] == 0  # no PASS before its row was durable
    assert "disk is full" in r.stderr or "full" in r.stderr
