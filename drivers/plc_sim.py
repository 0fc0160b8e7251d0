"""A simulated PLC speaking ``drivers.line_io``'s protocol, for sim runs and tests.

It sits on the far end of a real serial line: by default a pseudo-terminal pair made in-process
(``os.openpty``; no socat needed), whose other end the station opens like any serial port
(``SimulatedPLC.station_port``); or an existing port path, e.g. one end of a socat pty pair. It announces parts
(``TRIG <id>``) every ``trigger_period_s`` (or on ``trigger()``), acknowledges every decision (``ACK <id>``),
sends heartbeats, and records what it received so a sim run or a test can check every part got its decision.
"""

from __future__ import annotations

import logging
import os
import select
import threading
import time
import tty
from dataclasses import dataclass, field
from typing import Any

from drivers.line_io import Command

log = logging.getLogger(__name__)


class _PtyMaster:
    """The PLC's end of an in-process pty pair, with the subset of pyserial's API the PLC uses."""

    def __init__(self) -> None:
        self.fd, self._slave = os.openpty()
        tty.setraw(self._slave)  # no echo or line editing before the station configures the port itself
        self.station_port = os.ttyname(self._slave)

    def read(self, timeout_s: float) -> bytes:
        ready, _, _ = select.select([self.fd], [], [], timeout_s)
        return os.read(self.fd, 4096) if ready else b""

    def write(self, data: bytes) -> None:
        os.write(self.fd, data)

    def close(self) -> None:
        """Close both ends, once: a second call must not close the numbers the system has handed out since."""
        fds, self.fd, self._slave = (self.fd, self._slave), -1, -1
        for fd in fds:
            if fd >= 0:
                try:
                    os.close(fd)
                except OSError:
                    pass


class _SerialPort:
    def __init__(self, path: str, baudrate: int) -> None:
        import serial

        self._s = serial.Serial(path, baudrate=baudrate, timeout=0)
        self.station_port = None

    def read(self, timeout_s: float) -> bytes:
        ready, _, _ = select.select([self._s.fileno()], [], [], timeout_s)
        return self._s.read(4096) if ready else b""

    def write(self, data: bytes) -> None:
        self._s.write(data)

    def close(self) -> None:
        self._s.close()


@dataclass
class PLCRecord:
    """What the PLC sent and received; times are ``time.monotonic()`` seconds on the PLC's side."""

    triggers_sent: list[str] = field(default_factory=list)
    trigger_times: dict[str, float] = field(default_factory=dict)
    decisions: dict[str, str] = field(default_factory=dict)  # part id -> "PASS" or "REJECT <reason>" (``Command``)
    decision_times: dict[str, float] = field(default_factory=dict)  # part id -> first decision received
    acked: set[str] = field(default_factory=set)  # part ids the PLC acknowledged
    duplicate_decisions: int = 0
    heartbeats: int = 0
    errors: list[str] = field(default_factory=list)
    other: list[bytes] = field(default_factory=list)


class SimulatedPLC:
    """See the module docstring. ``trigger_period_s=None``: parts only on ``trigger()``; ``max_triggers``: the
    periodic triggers stop after that many parts (None: until closed)."""

    def __init__(self, *, port: str | None = None, baudrate: int = 115200, trigger_period_s: float | None = None,
                 heartbeat_s: float = 1.0, ack: bool = True, id_prefix: str = "P",
                 max_triggers: int | None = None) -> None:
        self.trigger_period_s, self.heartbeat_s, self.ack, self.id_prefix = (trigger_period_s, heartbeat_s, ack,
                                                                             id_prefix)
        self.max_triggers = max_triggers
        self._transport: Any = _SerialPort(port, baudrate) if port else _PtyMaster()
        self.station_port: str | None = self._transport.station_port
        self.record = PLCRecord()
        self._next = 1
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="plc-sim", daemon=True)

    def start(self) -> SimulatedPLC:
        self._thread.start()
        return self

    def trigger(self, part_id: str | None = None) -> str:
        """Announce one part now; returns its id."""
        with self._lock:
            if part_id is None:
                part_id = f"{self.id_prefix}{self._next}"
                self._next += 1
            self.record.triggers_sent.append(part_id)
            self.record.trigger_times[part_id] = time.monotonic()
        self.send(f"{Command.TRIG} {part_id}\n".encode())
        return part_id

    def send(self, data: bytes) -> None:
        """Write raw bytes to the station (tests use it for faults)."""
        with self._lock:
            self._transport.write(data)

    def wait_decisions(self, n: int, timeout_s: float) -> bool:
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            if len(self.record.decisions) >= n:
                return True
            time.sleep(0.005)
        return len(self.record.decisions) >= n

    def close(self) -> None:
        """Stop the PLC's thread, then close its port; safe to call twice. A thread still running 2 s later (a write
        blocked on a station that no longer reads) keeps its port open: closed under it, its next read could take
        whatever file the system gives that number next."""
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join(timeout=2)
            if self._thread.is_alive():
                log.warning("plc-sim: its thread did not stop within 2 s; its port is left open")
                return
        self._transport.close()

    def __enter__(self) -> SimulatedPLC:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _run(self) -> None:
        buf = b""
        now = time.monotonic()
        next_trig = now + (self.trigger_period_s or 0.0)
        next_hb = now
        while not self._stop.is_set():
            now = time.monotonic()
            try:
                feeding = self.trigger_period_s and (self.max_triggers is None
                                                     or len(self.record.triggers_sent) < self.max_triggers)
                if feeding and now >= next_trig:
                    self.trigger()
                    next_trig += self.trigger_period_s
                if self.heartbeat_s and now >= next_hb:
                    self.send(f"{Command.HB}\n".encode())
                    next_hb = now + self.heartbeat_s
                # the next trigger counts only while parts are still to come (once they are out, a next_trig left
                # in the past made this loop poll without pause)
                wait = min(t for t in (next_trig if feeding else now + 0.05, next_hb if
                                       self.heartbeat_s else now + 0.05, now + 0.05)) - now
                buf += self._transport.read(max(wait, 0.0))
            except OSError as exc:  # the station closed its end: keep the pty, wait for it to come back
                log.debug("plc-sim: %s", exc)
                time.sleep(0.05)
                continue
            *lines, buf = buf.split(b"\n")
            for line in lines:
                self._handle(line.rstrip(b"\r"))

    def _handle(self, line: bytes) -> None:
        text = line.decode("ascii", "replace")
        cmd, _, rest = text.partition(" ")
        if cmd in (Command.PASS, Command.REJECT):
            part_id, _, reason = rest.partition(" ")
            with self._lock:
                if part_id in self.record.decisions:
                    self.record.duplicate_decisions += 1
                else:
                    self.record.decision_times[part_id] = time.monotonic()
                self.record.decisions[part_id] = cmd if cmd == Command.PASS else f"{Command.REJECT} {reason}"
                if self.ack:
                    self.record.acked.add(part_id)
            if self.ack:
                self.send(f"{Command.ACK} {part_id}\n".encode())
        elif cmd == Command.HB:
            self.record.heartbeats += 1
        elif cmd == Command.ERR:
            self.record.errors.append(rest)
        else:
            self.record.other.append(line)
