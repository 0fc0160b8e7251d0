"""Fault injection: the station under hostile files, camera stalls, loss and power cycles, packet loss, a silent PLC,
a full disk, SIGTERM and a serial reconnect; per case parts announced, answered, logged, and the fail-open count.

Every case runs the real station (``station run`` in a subprocess, the shipped model with ``[decision] threshold =
1.0`` and no presence check, so that every part judged in time passes and any other pass is visible) against the
real parts: Aravis's fake GigE Vision camera on loopback (software trigger, 256 x 256 Mono8), the PLC link over a
socat pty pair with ``drivers.plc_sim.SimulatedPLC`` as a scripted PLC on the far end, the inspection log in
SQLite. The whole benchmark re-runs itself (``--worker``) in a private network and mount namespace: GigE Vision
stays on loopback (the network rule) and the full disk is a 600 KiB tmpfs that only the benchmark sees.

Columns: parts the station's host received (TRIG lines counted by its PLC link; the scripted PLC's count when the
station never started), decisions the PLC received, PASS among them, ACKs the PLC sent, log rows, rows whose
``io_delivered`` matches the PLC's ACK, unanswered parts (received, never answered) and fail-open: a PASS for a part
whose row is missing or not "pass", or that reached the PLC later than the cycle time (+50 ms for the serial
line), or a station that started on a hostile file. Targets: fail-open 0, rows = parts received, unanswered 0.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import sqlite3
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

from drivers.line_io import Command
from station.benchmarks.report import markdown_table, write_report
from station.commands.arguments import positive_int
from station.decision import Verdict

CASES = ("baseline", "hostile_files", "camera_stall", "packet_loss", "plc_silent", "full_disk", "sigterm",
         "serial_reconnect", "camera_killed", "camera_power_cycle")
SLACK_MS = 50.0
"""Serial line and scheduling time allowed on top of the cycle time before a PASS counts as too late."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--cases", default=",".join(CASES), help="comma-separated subset of: " + ", ".join(CASES))
    p.add_argument("--parts", type=positive_int, default=150, help="parts the PLC announces per case")
    p.add_argument("--loss-parts", type=int, default=1000, help="parts in the packet_loss case (2 %% loss)")
    p.add_argument("--trigger-period-ms", type=float, default=150.0, help="time between the PLC's triggers")
    p.add_argument("--cycle-time-ms", type=float, default=300.0, help="[acquisition] cycle_time_ms")
    p.add_argument("--model", default="model/weights/default", help="model checkpoint (path without suffix)")
    p.add_argument("--worker", default=None, help=argparse.SUPPRESS)


@dataclass
class CaseResult:
    case: str
    announced: int = 0
    decisions: int = 0
    passes: int = 0
    acks: int = 0
    rows: int = 0
    io_right: int = 0
    unanswered: int = 0
    fail_open: int = 0
    note: str = ""
    seconds: float = 0.0
    extra: dict[str, Any] = field(default_factory=dict)


# -- the parts (worker side, inside the namespaces) ----------------------------------------------------------------
class FakeCamera:
    def __init__(self, loss_per_mille: int = 0) -> None:
        self.loss_per_mille = loss_per_mille
        self.restart()

    def restart(self) -> None:
        """A camera (again) at the same address: after a kill, a power-cycled camera coming back."""
        from drivers.netns import start_fake_gv_camera

        old = getattr(self, "proc", None)
        if old is not None:  # reaped (or killed, if still running)
            old.kill()
            old.wait()
        self.proc = start_fake_gv_camera("FAULTS", self.loss_per_mille)

    def signal(self, sig: int) -> None:
        if self.proc.poll() is None:
            self.proc.send_signal(sig)

    def close(self) -> None:
        self.signal(signal.SIGCONT)
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()


class PtyPair:
    """``socat`` pty pair with stable names: the station's end and the PLC's end."""

    def __init__(self, folder: Path) -> None:
        self.station, self.plc = str(folder / "station-tty"), str(folder / "plc-tty")
        self.proc: subprocess.Popen[bytes] | None = None
        self.start()

    def start(self) -> None:
        self.proc = subprocess.Popen(["socat", f"pty,raw,echo=0,link={self.station}",
                                      f"pty,raw,echo=0,link={self.plc}"], stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 5
        while not (Path(self.station).exists() and Path(self.plc).exists()):
            if time.monotonic() > deadline:
                raise RuntimeError("socat did not create its ptys")
            time.sleep(0.01)

    def kill(self) -> None:
        if self.proc is not None and self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        for p in (self.station, self.plc):
            Path(p).unlink(missing_ok=True)


def station_toml(folder: Path, args: argparse.Namespace, port: str, log_path: Path, **over: str) -> Path:
    """The station's configuration for one case; ``over``: "section.key" -> TOML value text."""
    values = {
        "camera.kind": '"aravis"', "camera.device": '"127.0.0.1"', "camera.pixel_format": '"Mono8"',
        "camera.width": "256", "camera.height": "256", "camera.trigger": '"software"', "camera.timeout_ms": "500",
        "camera.frame_rate_hz": "25.0", "camera.exposure_us": "1000.0",
        "acquisition.cycle_time_ms": str(args.cycle_time_ms), "acquisition.queue_size": "4",
        "model.path": json.dumps(str(Path(args.model).resolve())), "decision.threshold": "1.0",
        "presence.enabled": "false", "io.mode": '"serial"', "io.port": json.dumps(port), "io.heartbeat_s": "1.0",
        "log.path": json.dumps(str(log_path)), "log.save_rejects": "false", "log.retention_days": "0",
    }
    values.update(over)
    sections: dict[str, list[str]] = {}
    for key, value in values.items():
        section, name = key.split(".")
        sections.setdefault(section, []).append(f"{name} = {value}")
    path = folder / "station.toml"
    path.write_text("".join(f"[{s}]\n" + "\n".join(lines) + "\n\n" for s, lines in sections.items()))
    return path


def start_station(config: Path, summary: Path, frames: int | None = None) -> subprocess.Popen[str]:
    """``station run`` on ``config``; ``frames``: stop after that many parts (None: until SIGTERM)."""
    argv = [sys.executable, "-m", "station.cli", "run", "--config", str(config), "--summary-json", str(summary)]
    if frames:
        argv += ["--frames", str(frames)]
    return subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def wait_for(cond: Callable[[], bool], timeout_s: float) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if cond():
            return True
        time.sleep(0.02)
    return cond()


def read_rows(log_path: Path) -> list[dict[str, Any]]:
    if not log_path.exists():
        return []
    con = sqlite3.connect(f"file:{log_path}?mode=ro", uri=True)
    con.row_factory = sqlite3.Row
    try:
        return [dict(r) for r in con.execute("SELECT part_id, decision, io_delivered FROM inspections")]
    except sqlite3.Error:
        return []
    finally:
        con.close()


def score(case: str, plcs: list[Any], rows: list[dict[str, Any]], summary: dict[str, Any] | None,
          cycle_time_ms: float) -> CaseResult:
    """Compare what the PLC saw with the station's log (``CaseResult`` columns)."""
    decisions: dict[str, str] = {}
    t_trig: dict[str, float] = {}
    t_dec: dict[str, float] = {}
    acked: set[str] = set()
    sent = 0
    for plc in plcs:
        r = plc.record
        decisions.update(r.decisions)
        t_trig.update(r.trigger_times)
        t_dec.update(r.decision_times)
        acked |= r.acked
        sent += len(r.triggers_sent)
    link = (summary or {}).get("plc_link") or {}
    received = int(link.get("triggers", sent))
    by_part = {}
    for row in rows:
        by_part.setdefault(row["part_id"], []).append(row)
    fail_open = 0
    for part, d in decisions.items():
        if d != Command.PASS:
            continue
        mine = by_part.get(part, [])
        late_ms = 1e3 * (t_dec.get(part, 0.0) - t_trig.get(part, 0.0))
        if len(mine) != 1 or mine[0]["decision"] != Verdict.PASS or late_ms > cycle_time_ms + SLACK_MS:
            fail_open += 1
    io_right = sum(1 for row in rows if bool(row["io_delivered"]) == (row["part_id"] in acked))
    return CaseResult(case, announced=received, decisions=len(decisions),
                      passes=sum(d == Command.PASS for d in decisions.values()), acks=len(acked), rows=len(rows),
                      io_right=io_right, unanswered=max(0, received - len(decisions)), fail_open=fail_open,
                      extra={"plc_sent": sent, "duplicate_rows": sum(len(v) - 1 for v in by_part.values()),
                             "summary": summary})


def run_case(case: str, args: argparse.Namespace, work: Path) -> CaseResult:
    from drivers.plc_sim import SimulatedPLC

    folder = work / case
    folder.mkdir(parents=True, exist_ok=True)
    log_path = folder / "inspection.sqlite"
    summary_path = folder / "summary.json"
    if case == "hostile_files":
        return hostile_files(args, folder)
    n = args.loss_parts if case == "packet_loss" else args.parts
    camera = FakeCamera(loss_per_mille=20 if case == "packet_loss" else 0)
    pair = PtyPair(folder)
    over: dict[str, str] = {}
    disk: Path | None = None
    if case == "full_disk":
        disk = folder / "small-disk"
        disk.mkdir()
        subprocess.run(["mount", "-t", "tmpfs", "-o", "size=600k", "tmpfs", str(disk)], check=True)
        log_path = disk / "inspection.sqlite"
    config = station_toml(folder, args, pair.station, log_path, **over)
    t0 = time.perf_counter()
    proc = start_station(config, summary_path)
    plcs = [SimulatedPLC(port=pair.plc, trigger_period_s=None, heartbeat_s=1.0, id_prefix="A")]
    plcs[0].start()
    note = ""
    try:
        if not wait_for(lambda: "inspecting with camera" in _peek(proc), 120):
            raise RuntimeError(f"station did not start: {_drain(proc)[-600:]}")
        filler = disk / "filler" if disk else None
        if filler is not None:  # fill the disk but for ~48 KiB: the log fills within a few dozen parts
            _fill(filler, leave_bytes=48 * 1024)
        period = args.trigger_period_ms / 1e3
        for i in range(n):
            if proc.poll() is not None:
                break
            plc = plcs[-1]
            if case == "camera_stall" and i == n // 3:  # the triggers keep coming during the stall
                camera.signal(signal.SIGSTOP)
                threading.Timer(3.0, camera.signal, (signal.SIGCONT,)).start()
                note = "camera stopped (SIGSTOP) for 3 s at 1/3, triggers continue"
            if case == "plc_silent" and i == n // 2:
                plc.ack = False
                note = "PLC stops acknowledging halfway"
            if case == "full_disk" and filler is not None and i == 2 * n // 3:
                filler.unlink()
                note = "600 KiB tmpfs filled; space freed at 2/3 of the run"
            if case == "sigterm" and i == n // 2:
                proc.send_signal(signal.SIGTERM)
                note = "SIGTERM halfway, triggers continue"
            if case == "camera_killed" and i == n // 3:
                camera.signal(signal.SIGKILL)
                note = "camera killed (SIGKILL) at 1/3, triggers continue until the station exits"
            if case == "camera_power_cycle" and i == n // 3:
                camera.signal(signal.SIGKILL)
                threading.Timer(1.0, camera.restart).start()
                note = "camera killed (SIGKILL) at 1/3 and back 1 s later (reconnect on), triggers continue"
            if case == "serial_reconnect" and i == n // 2:
                plc.close()
                pair.kill()
                time.sleep(1.0)
                pair.start()
                plcs.append(SimulatedPLC(port=pair.plc, trigger_period_s=None, heartbeat_s=1.0, id_prefix="B"))
                plcs[-1].start()
                plc = plcs[-1]
                note = "socat killed halfway and restarted after 1 s"
            try:
                plc.trigger()
            except OSError:
                pass
            time.sleep(period)
        if case in ("sigterm", "camera_killed"):
            deadline = time.monotonic() + (60 if case == "camera_killed" else 15)
            while proc.poll() is None and time.monotonic() < deadline:  # the line keeps announcing parts
                try:
                    plcs[-1].trigger()
                except OSError:
                    pass
                time.sleep(period)
        else:  # the line stops feeding; once the answers have settled, the operator stops the station
            answered = -1
            while proc.poll() is None and answered != sum(len(p.record.decisions) for p in plcs):
                answered = sum(len(p.record.decisions) for p in plcs)
                time.sleep(2.0)
            proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=90)
    except Exception as exc:
        note = f"{note}; harness: {exc}".strip("; ")
        proc.kill()
        proc.wait()
    finally:
        time.sleep(0.5)  # the last ACKs on their way
        for plc in plcs:
            plc.close()
        pair.kill()
        camera.close()
    stderr = _drain(proc)
    summary = json.loads(summary_path.read_text()) if summary_path.exists() else None
    rows = read_rows(log_path)
    if disk is not None:
        subprocess.run(["umount", str(disk)], check=False)
    result = score(case, plcs, rows, summary, args.cycle_time_ms)
    result.note, result.seconds = note, time.perf_counter() - t0
    result.extra.update(exit_code=proc.returncode, unrecorded_rows_in_stderr=stderr.count("UNRECORDED ROW"),
                        stderr_tail=stderr[-400:])
    return result


_OUTPUT: dict[int, str] = {}


def _peek(proc: subprocess.Popen[str]) -> str:
    """The station's stdout so far (non-blocking)."""
    import selectors

    sel = selectors.DefaultSelector()
    sel.register(proc.stdout, selectors.EVENT_READ)  # type: ignore[arg-type]
    while sel.select(timeout=0):
        line = proc.stdout.readline()  # type: ignore[union-attr]
        if not line:
            break
        _OUTPUT[proc.pid] = _OUTPUT.get(proc.pid, "") + line
    sel.close()
    return _OUTPUT.get(proc.pid, "")


def _drain(proc: subprocess.Popen[str]) -> str:
    try:
        _, err = proc.communicate(timeout=10)
    except (subprocess.TimeoutExpired, ValueError):
        err = ""
    return err or ""


def _fill(path: Path, leave_bytes: int) -> None:
    """Write ``path`` until the file system is full, then give back ``leave_bytes``."""
    with open(path, "wb", buffering=0) as f:
        try:
            while True:
                f.write(b"\0" * 4096)
        except OSError:
            pass
    size = path.stat().st_size
    with open(path, "r+b") as f:
        f.truncate(max(0, size - leave_bytes))


def hostile_files(args: argparse.Namespace, folder: Path) -> CaseResult:
    """Each hostile file or key must stop the station before any part, with one line naming it."""
    model = Path(args.model)
    bad = folder / "models"
    bad.mkdir(exist_ok=True)

    def model_copy(name: str, edit: Callable[[dict[str, Any]], Any]) -> str:
        stem = bad / name
        shutil.copy(model.with_suffix(".pt"), stem.with_suffix(".pt"))
        meta = json.loads(model.with_suffix(".json").read_text())
        meta["weights_file"] = stem.with_suffix(".pt").name
        new = edit(meta)
        meta = meta if new is None else new
        stem.with_suffix(".json").write_text(json.dumps(meta, allow_nan=True))
        return json.dumps(str(stem))

    def set_key(key: str, value: Any) -> Callable[[dict[str, Any]], None]:
        return lambda m: m.__setitem__(key, value)

    foreign = folder / "foreign.sqlite"
    con = sqlite3.connect(foreign)
    con.execute("PRAGMA user_version=99")
    con.close()
    cases = {
        "sidecar threshold NaN": ({"model.path": model_copy("nan", set_key("threshold", float("nan")))}, "threshold"),
        "sidecar threshold 2.0": ({"model.path": model_copy("two", set_key("threshold", 2.0))}, "threshold"),
        "sidecar threshold 'abc'": ({"model.path": model_copy("abc", set_key("threshold", "abc"))}, "threshold"),
        "sidecar std 0": ({"model.path": model_copy("std", lambda m: m["normalization"].__setitem__(
            "std", [0.0] * len(m["normalization"]["std"])))}, "normalization"),
        "sidecar is []": ({"model.path": model_copy("list", lambda m: [])}, "not a JSON object"),
        "weights_file outside": ({"model.path": model_copy("outside", set_key("weights_file", "../x.pt"))},
                                 "weights_file"),
        "[model] path empty": ({"model.path": '""'}, "[model] path"),
        "[model] device cuda": ({"model.device": '"cuda"'}, "[model] device"),
        "[decision] threshold NaN": ({"decision.threshold": "nan"}, "threshold"),
        "camera ROI 4000x4000": ({"camera.width": "4000", "camera.height": "4000"}, "width"),
        "log: foreign SQLite": ({"log.path": json.dumps(str(foreign))}, "schema version 99"),
    }
    started, one_line, details = 0, 0, {}
    camera = FakeCamera()
    pair = PtyPair(folder)
    try:
        for name, (over, needle) in cases.items():
            sub = folder / name.replace(" ", "_").replace("'", "").replace("[", "").replace("]", "")
            sub.mkdir(exist_ok=True)
            config = station_toml(sub, args, pair.station, sub / "log.sqlite", **over)
            proc = start_station(config, sub / "summary.json", frames=1)
            try:
                out, err = proc.communicate(timeout=120)
            except subprocess.TimeoutExpired:
                proc.kill()
                out, err = proc.communicate()
            lines = [x for x in err.strip().splitlines() if x.startswith("station run: error:")]
            ok = proc.returncode == 2 and len(lines) == 1 and needle in lines[0] and "Traceback" not in err
            started += "inspecting with camera" in out
            one_line += ok
            details[name] = lines[0][:160] if lines else err.strip().splitlines()[-1:] or [""]
    finally:
        pair.kill()
        camera.close()
    return CaseResult("hostile_files", fail_open=started, note=f"{one_line} of {len(cases)} refused with one line "
                      "naming the file or key", extra={"errors": details})


def worker(args: argparse.Namespace) -> int:
    out = Path(args.worker)
    results = []
    work = Path(args.out).resolve() / "work"  # each case's config, log and summary, kept for a look afterwards
    shutil.rmtree(work, ignore_errors=True)
    for case in args.cases.split(","):
        print(f"[faults] {case} ...", file=sys.stderr, flush=True)
        try:
            results.append(asdict(run_case(case, args, work)))
        except Exception as exc:  # one broken case must not hide the others
            results.append(asdict(CaseResult(case, note=f"harness error: {type(exc).__name__}: {exc}")))
        out.write_text(json.dumps(results, indent=1, default=str))
        r = results[-1]
        print(f"[faults] {case}: announced {r['announced']}, rows {r['rows']}, fail-open {r['fail_open']} "
              f"({r['seconds']:.0f} s) {r['note']}", file=sys.stderr, flush=True)
    return 0


# -- the parent: namespaces, table, report -------------------------------------------------------------------------
def namespaces_unavailable_reason() -> str | None:
    for tool in ("unshare", "ip", "socat", "arv-fake-gv-camera-0.8", "mount"):
        if shutil.which(tool) is None:
            return f"'{tool}' is not installed"
    if os.geteuid() != 0:
        return "needs root for a private mount namespace with tmpfs"
    r = subprocess.run(["unshare", "-n", "-m", "sh", "-c", "ip link set lo up && mount -t tmpfs -o size=64k tmpfs "
                        "/mnt"], capture_output=True, text=True)
    return None if r.returncode == 0 else f"unshare -n -m failed: {r.stderr.strip()}"


def run(args: argparse.Namespace) -> int:
    from station.errors import UserError

    if args.worker:
        return worker(args)
    unknown = set(args.cases.split(",")) - set(CASES)
    if unknown:
        raise UserError(f"--cases: unknown {', '.join(sorted(unknown))}; choose from {', '.join(CASES)}")
    why = namespaces_unavailable_reason()
    if why:
        raise UserError(f"station bench faults: {why}")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows_file = out / "cases.json"
    argv = [sys.executable, "-m", "station.cli", "bench", "faults", "--worker", str(rows_file.resolve()),
            "--cases", args.cases, "--parts", str(args.parts), "--loss-parts", str(args.loss_parts),
            "--trigger-period-ms", str(args.trigger_period_ms), "--cycle-time-ms", str(args.cycle_time_ms),
            "--model", args.model, "--out", args.out]
    inner = "ip link set lo up && mount --make-rprivate / && exec " + " ".join(f"'{a}'" for a in argv)
    subprocess.run(["unshare", "-n", "-m", "sh", "-c", inner], check=False)
    results = json.loads(rows_file.read_text()) if rows_file.exists() else []
    names = {"case": "case", "announced": "parts received", "decisions": "PLC decisions", "passes": "PASS",
             "acks": "ACKs", "rows": "rows", "io_right": "rows io_delivered right", "unanswered": "unanswered",
             "fail_open": "fail-open", "note": "note"}
    table = markdown_table([{names[k]: r[k] for k in names} for r in results], list(names.values()))
    print(table)
    write_report(out, "faults", {"cases": results, "parts": args.parts, "cycle_time_ms": args.cycle_time_ms,
                                 "trigger_period_ms": args.trigger_period_ms}, table)
    bad = [r["case"] for r in results if r["fail_open"] or r["unanswered"] or (r["case"] != "hostile_files"
                                                                                and r["rows"] != r["announced"])]
    if bad:
        print(f"cases off target: {', '.join(bad)}")
    return 0
