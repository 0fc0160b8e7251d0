"""Trigger / reject line protocol with the PLC over a serial line (pyserial), with reconnect and no lost decisions.

Protocol (also in docs/drivers.md). ASCII lines ending in ``\\n`` (a ``\\r`` before it is ignored), at most
``MAX_LINE_BYTES`` bytes including the ``\\n``. Tokens are separated by one space. A part id is 1-32 characters
of ``[A-Za-z0-9_.:-]``.

    PLC -> station   TRIG <id>            a part is in front of the camera
                     ACK <id>             the PLC took the station's decision for <id>
                     HB                   heartbeat
                     ERR <text>           the PLC reports a problem (logged)
    station -> PLC   PASS <id>            part <id> is good
                     REJECT <id> <reason> part <id> must be ejected; <reason> is one token ([a-z0-9_])
                     HB                   heartbeat, every ``heartbeat_s``
                     ERR <text>           the station refuses a line (over-long, not ASCII, unknown command,
                                          bad or duplicate id)

Triggers are timestamped when their line reaches the host (``Trigger.t_arrival``, ``time.perf_counter()``), so
the station measures a part's age from the PLC's announcement, not from when it got round to it.
``expired(before)`` takes out triggers that waited too long (the station answers them as late while its camera
is busy); after ``refuse_triggers(handler)`` (shutdown) every trigger, queued or new, is answered REJECT with the
reason ``handler`` returns, in the I/O thread, so no announced part goes unanswered until the port closes.

Delivery: a decision stays pending until the PLC sends ``ACK <id>``. If no ACK comes within ``ack_timeout_ms``
it is sent again (at most ``max_resends`` times); while the link is down decisions wait in the queue and go out,
in order, after the reconnect. A decision that still has no ACK after its resends, or is pending when the link is
closed, is reported undelivered: an ERROR log line and ``on_undelivered(part_id, line)``, and it is listed by
``undelivered()``. With ``require_ack=False`` a decision counts as delivered once written. ``outcomes()`` hands
out each settled decision once: (part id, acknowledged or given up, when, the decision as sent). A PASS reported
with a ``deadline`` is never written as PASS after it: sent, resent or sent again after a reconnect once the
deadline has passed, it goes out as ``REJECT <id> late_link``.

Faults: the peer disappearing shows as ``SerialException``/``OSError`` on read or write; the link is closed,
logged once, and reopened with back-off (``reconnect_backoff_s`` doubling to ``reconnect_backoff_max_s``).
Garbage, over-long lines, unknown commands and duplicate trigger ids are logged, counted and answered with ERR.
Silence longer than ``3 * heartbeat_s`` (with a heartbeat configured) is logged as a stale link.

``LineIO`` implements ``station.line_link.LineLink``. The words of the protocol are ``Command``; a part's decision is a
``Verdict`` (defined here, see there why).
"""

from __future__ import annotations

import collections
import dataclasses
import logging
import math
import re
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

from drivers.camera import backoff_delays_s
from drivers.errors import LineIOError

log = logging.getLogger(__name__)

MAX_LINE_BYTES = 64
POLL_MS = 5
"""The I/O thread's read timeout: a decision queued while it waits goes out at most this much later (it was 50 ms,
half a 100 ms cycle). Incoming lines wake it at once either way."""
PART_ID = re.compile(r"[A-Za-z0-9_.:-]{1,32}")
REASON_CHARS = re.compile(r"[^a-z0-9_]+")


class Verdict(StrEnum):
    """What became of a part: the station's one set of decision values (``station.decision`` re-exports it; the
    inspection log stores them, ``station.inspection_log.DECISIONS``).

    It is defined here, in the PLC protocol's module, because the line and the station both need it and only
    ``drivers`` lies below both: ``drivers`` may not import ``station``, the station imports ``drivers``. The
    protocol carries two of the values (``decision_line``: ``PASS`` for PASS, ``REJECT`` for anything else, failing
    closed); EMPTY and NOT_INSPECTED are the station's own (what it logs for a view without a part and for a frame
    dropped before judgement). Members are ``str``: they compare equal to their values and are stored, exported and
    formatted as them, so the SQLite log, JSON, CSV and the PLC's lines are the same bytes as with plain strings."""

    PASS = "pass"
    """Judged good (score <= threshold)."""
    REJECT = "reject"
    """Judged bad (score > threshold), or could not be judged (fail closed; a reason says why)."""
    EMPTY = "empty"
    """No part in view: not judged (an announced part not in view is answered REJECT)."""
    NOT_INSPECTED = "not_inspected"
    """Frame dropped before judgement (queue full, grab failure; an announced part is answered REJECT)."""


class Command(StrEnum):
    """The first word of a protocol line (module docstring), as it goes over the wire."""

    TRIG = "TRIG"
    ACK = "ACK"
    HB = "HB"
    ERR = "ERR"
    PASS = "PASS"
    REJECT = "REJECT"


@dataclass(frozen=True)
class LineIOConfig:
    """port: a device path ("/dev/ttyUSB0") or a pyserial URL; baudrate in bit/s; timeout_ms: the read poll and
    write timeout; heartbeat_s: 0 = none; triggered: False = trigger-free (parts are not announced by the PLC,
    decisions are still reported)."""

    port: str
    baudrate: int = 115200
    timeout_ms: int = 500
    heartbeat_s: float = 1.0
    triggered: bool = True
    require_ack: bool = True
    ack_timeout_ms: int = 1000
    max_resends: int = 3
    reconnect_backoff_s: float = 0.2
    reconnect_backoff_max_s: float = 5.0
    duplicate_window: int = 4096
    duplicate_window_s: float = 10.0
    """A TRIG id seen again within this many seconds (and among the last ``duplicate_window`` ids) is the same part
    announced again (ERR duplicate id); later, it is a new part: a PLC whose counter restarted or wrapped."""
    max_line_bytes: int = MAX_LINE_BYTES


@dataclass
class LineIOStats:
    triggers: int = 0
    duplicates: int = 0
    garbage: int = 0
    too_long: int = 0
    unknown: int = 0
    plc_errors: int = 0
    heartbeats_in: int = 0
    decisions: int = 0
    sent: int = 0
    acked: int = 0
    resent: int = 0
    undelivered: int = 0
    disconnects: int = 0
    reconnects: int = 0


@dataclass(frozen=True)
class Trigger:
    """A part the PLC announced: its id and when the TRIG line reached the host (``time.perf_counter()`` s)."""

    part_id: str
    t_arrival: float


@dataclass
class _Pending:
    part_id: str
    line: bytes
    sent_at: float | None = None  # monotonic time of the last send; None = not yet sent
    sends: int = 0
    deadline: float | None = None  # perf_counter time after which a PASS is written as REJECT (_too_late_to_pass)

    @property
    def decision(self) -> Verdict:
        """PASS or REJECT: what the line says."""
        return Verdict.PASS if self.line.startswith(f"{Command.PASS} ".encode()) else Verdict.REJECT


def reason_token(reason: str | None) -> str:
    """A free-text reason -> one protocol token: lower case, [a-z0-9_], at most 24 characters."""
    token = REASON_CHARS.sub("_", (reason or "rejected").lower()).strip("_")[:24]
    return token or "rejected"


def decision_line(part_id: str, decision: Verdict | str, reason: str | None) -> bytes:
    """``PASS <id>`` for decision PASS, else ``REJECT <id> <reason>`` (fail closed: anything but a pass rejects)."""
    if not PART_ID.fullmatch(part_id):
        raise LineIOError(f"part id {part_id!r}: not 1-32 characters of [A-Za-z0-9_.:-]")
    text = (f"{Command.PASS} {part_id}" if decision == Verdict.PASS
            else f"{Command.REJECT} {part_id} {reason_token(reason)}")
    return (text + "\n").encode("ascii")


class LineIO:
    """The station's end of the PLC link; one background thread owns the serial port."""

    def __init__(self, config: LineIOConfig, *, on_undelivered: Callable[[str, str], None] | None = None,
                 serial_factory: Callable[[LineIOConfig], Any] | None = None) -> None:
        self.config = config
        self.triggered = config.triggered
        self.on_undelivered = on_undelivered
        self._factory = serial_factory or _open_serial
        self._triggers: collections.deque[Trigger] = collections.deque()
        self._trigger_cond = threading.Condition()
        self._refusing: Callable[[Trigger], str] | None = None
        self._outcomes: list[tuple[str, bool, float, Verdict]] = []
        self._outbox: collections.deque[_Pending] = collections.deque()  # not yet written
        self._inflight: dict[str, _Pending] = {}  # written, waiting for ACK
        self._undelivered: list[tuple[str, str]] = []
        self._seen: collections.OrderedDict[str, float] = collections.OrderedDict()  # TRIG id -> arrival
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._link_up = threading.Event()
        self._thread: threading.Thread | None = None
        self._port: Any = None
        self.stats = LineIOStats()

    # -- public API -------------------------------------------------------------------------------------------
    def start(self) -> None:
        """Open the port (``LineIOError`` naming it if that fails) and start the I/O thread."""
        try:
            self._port = self._factory(self.config)
        except (OSError, ValueError, ImportError) as exc:  # SerialException is an OSError
            raise LineIOError(f"PLC port {self.config.port!r}: cannot open: {exc}") from None
        self._link_up.set()
        self._thread = threading.Thread(target=self._run, name="line-io", daemon=True)
        self._thread.start()
        log.info("PLC link on %s at %d baud (%s)", self.config.port, self.config.baudrate,
                 "triggered" if self.triggered else "trigger-free")

    @property
    def link_up(self) -> bool:
        return self._link_up.is_set()

    has_plc = True
    """A PLC answers (``station.line_link.LineLink``): decisions are pending until ``outcomes`` settles them."""

    def next_trigger(self, timeout_s: float) -> Trigger | None:
        """The oldest part the PLC announced and nobody took yet, or None after ``timeout_s``."""
        with self._trigger_cond:
            if not self._trigger_cond.wait_for(lambda: self._triggers, timeout=timeout_s):
                return None
            return self._triggers.popleft()

    def expired(self, before: float) -> list[Trigger]:
        """Take out the waiting triggers that arrived before ``before`` (``time.perf_counter()`` s)."""
        with self._trigger_cond:
            out = []
            while self._triggers and self._triggers[0].t_arrival < before:
                out.append(self._triggers.popleft())
            return out

    def refuse_triggers(self, handler: Callable[[Trigger], str]) -> None:
        """From now on answer every trigger REJECT at once with the reason ``handler(trigger)`` returns (called in
        the caller's thread for those already waiting, then in the I/O thread; it may record the part first)."""
        with self._trigger_cond:
            self._refusing = handler
            waiting = list(self._triggers)
            self._triggers.clear()
        for t in waiting:
            self.report(t.part_id, Verdict.REJECT, handler(t))

    def report(self, part_id: str, decision: Verdict | str, reason: str | None,
               deadline: float | None = None) -> bool | None:
        """Queue PASS/REJECT for ``part_id``; False: sent once the link is up, acknowledged later (``outcomes``).
        ``deadline`` (``time.perf_counter()`` s): a PASS written after it (the link was down, or the PLC did not
        acknowledge and it is resent) goes out as ``REJECT <id> late_link`` instead, since the part has moved on.
        Never blocks and never drops."""
        line = decision_line(part_id, decision, reason)
        with self._lock:
            self.stats.decisions += 1
            self._outbox.append(_Pending(part_id, line, deadline=deadline))
        return False

    def outcomes(self) -> list[tuple[str, bool, float, Verdict]]:
        """Decisions settled since the last call: (part id, True, when, sent) acknowledged by the PLC (or written,
        without ACKs), (part id, False, when, sent) given up undelivered; ``when`` in ``time.perf_counter()`` s,
        ``sent`` the decision as it went out (PASS or REJECT: a late PASS goes out as a reject)."""
        with self._lock:
            out, self._outcomes = self._outcomes, []
        return out

    def undelivered(self) -> list[tuple[str, str]]:
        """(part id, decision line) of every decision reported undelivered so far."""
        with self._lock:
            return list(self._undelivered)

    def pending(self) -> int:
        """Decisions not yet acknowledged (queued or in flight)."""
        with self._lock:
            return len(self._outbox) + len(self._inflight)

    def flush(self, timeout_s: float) -> bool:
        """Wait until every decision is acknowledged (or written, without ACKs); True if that happened."""
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            if self.pending() == 0:
                return True
            time.sleep(0.01)
        return self.pending() == 0

    def close(self, flush_timeout_s: float = 1.0) -> list[tuple[str, str]]:
        """Flush (up to ``flush_timeout_s``), stop, report what is still pending as undelivered; return all
        undelivered decisions."""
        if self._thread is not None:  # a second close has nothing left to do
            self.flush(flush_timeout_s)
            self._stop.set()
            self._thread.join(timeout=5)
            self._thread = None
        with self._lock:
            left = list(self._outbox) + list(self._inflight.values())
            self._outbox.clear()
            self._inflight.clear()
        for p in left:
            self._give_up(p, "link closed before the PLC acknowledged it")
        self._close_port()
        return self.undelivered()

    def __enter__(self) -> LineIO:
        self.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    # -- I/O thread -------------------------------------------------------------------------------------------
    def _run(self) -> None:
        buf = bytearray()
        discarding = False
        last_hb = 0.0
        last_rx = time.monotonic()
        stale_logged = False
        while not self._stop.is_set():
            if self._port is None and not self._reconnect():
                break
            try:
                now = time.monotonic()
                hb = self.config.heartbeat_s
                if hb and now - last_hb >= hb:
                    self._write(f"{Command.HB}\n".encode())
                    last_hb = now
                self._send_due(now)
                chunk = self._port.read(max(1, self._port.in_waiting))
            except (OSError, ValueError) as exc:  # SerialException (an OSError), EIO, or a port closed under us
                self._lost(exc)
                buf.clear()
                discarding = False
                continue
            if chunk:
                last_rx, stale_logged = time.monotonic(), False
                buf += chunk
                while True:
                    nl = buf.find(b"\n")
                    if nl < 0:
                        if len(buf) >= self.config.max_line_bytes:
                            if not discarding:
                                self._refuse("too_long", f"line over {self.config.max_line_bytes} bytes", buf[:24])
                            discarding = True
                            buf.clear()
                        break
                    line, buf = bytes(buf[:nl]), buf[nl + 1:]
                    if discarding:  # the tail of an over-long line
                        discarding = False
                        continue
                    if len(line) + 1 > self.config.max_line_bytes:
                        self._refuse("too_long", f"line over {self.config.max_line_bytes} bytes", line[:24])
                        continue
                    self._handle(line.rstrip(b"\r"))
            elif hb and time.monotonic() - last_rx > 3 * hb and not stale_logged:
                log.warning("PLC link %s: nothing received for %.1f s (heartbeat %.1f s)", self.config.port,
                            time.monotonic() - last_rx, hb)
                stale_logged = True

    def _handle(self, line: bytes) -> None:
        t_arrival = time.perf_counter()
        try:
            text = line.decode("ascii")
        except UnicodeDecodeError:
            self._refuse("garbage", "not ASCII", line[:24])
            return
        if not text or not text.isprintable():
            self._refuse("garbage", "empty or control characters", line[:24])
            return
        cmd, _, arg = text.partition(" ")
        if cmd == Command.HB and not arg:
            self.stats.heartbeats_in += 1
        elif cmd == Command.TRIG:
            if not PART_ID.fullmatch(arg):
                self._refuse("garbage", "bad part id", line)
            elif t_arrival - self._seen.get(arg, -math.inf) < self.config.duplicate_window_s:
                self.stats.duplicates += 1
                log.warning("PLC link %s: duplicate trigger id %r ignored", self.config.port, arg)
                self._write(f"{Command.ERR} duplicate id {arg}\n".encode())
            else:
                self._seen.pop(arg, None)
                self._seen[arg] = t_arrival
                if len(self._seen) > self.config.duplicate_window:
                    self._seen.popitem(last=False)
                self.stats.triggers += 1
                if self.triggered:
                    trigger = Trigger(arg, t_arrival)
                    with self._trigger_cond:
                        refuse = self._refusing
                        if refuse is None:
                            self._triggers.append(trigger)
                            self._trigger_cond.notify_all()
                    if refuse is not None:
                        self.report(arg, Verdict.REJECT, refuse(trigger))
                else:
                    log.debug("trigger-free mode: TRIG %s ignored", arg)
        elif cmd == Command.ACK and PART_ID.fullmatch(arg):
            with self._lock:
                p = self._inflight.pop(arg, None)
                if p is not None:
                    self._outcomes.append((arg, True, t_arrival, p.decision))
            if p is None:
                log.info("PLC link %s: ACK for %r, which is not pending (late or repeated)", self.config.port, arg)
            else:
                self.stats.acked += 1
        elif cmd == Command.ERR:
            self.stats.plc_errors += 1
            log.error("PLC reports: %s", arg)
        else:
            self._refuse("unknown", f"unknown command {cmd[:16]!r}", line)

    def _refuse(self, counter: str, why: str, sample: bytes | bytearray) -> None:
        setattr(self.stats, counter, getattr(self.stats, counter) + 1)
        log.warning("PLC link %s: %s: %r", self.config.port, why, bytes(sample))
        try:
            self._write(f"{Command.ERR} {why}"[: self.config.max_line_bytes - 1].encode("ascii", "replace") + b"\n")
        except (OSError, ValueError):
            pass  # the read path will notice a dead link

    def _send_due(self, now: float) -> None:
        """Write queued decisions; resend or give up on those whose ACK is overdue."""
        ack_s = self.config.ack_timeout_ms / 1e3
        with self._lock:
            overdue = [p for p in self._inflight.values() if p.sent_at is not None and now - p.sent_at > ack_s]
        for p in overdue:
            if p.sends > self.config.max_resends:
                with self._lock:
                    self._inflight.pop(p.part_id, None)
                self._give_up(p, f"no ACK after {p.sends} sends")
            else:
                self._too_late_to_pass(p)
                self._write(p.line)
                p.sent_at, p.sends = time.monotonic(), p.sends + 1
                self.stats.resent += 1
        while True:
            with self._lock:
                if not self._outbox:
                    return
                p = self._outbox[0]
                self._too_late_to_pass(p)
            self._write(p.line)  # raises on a dead link: p stays queued
            p.sent_at, p.sends = time.monotonic(), p.sends + 1
            self.stats.sent += 1
            with self._lock:
                self._outbox.popleft()
                if self.config.require_ack:
                    self._inflight[p.part_id] = p
                else:
                    self._outcomes.append((p.part_id, True, time.perf_counter(), p.decision))

    def _too_late_to_pass(self, p: _Pending) -> None:
        """A PASS about to be written (first send, resend, or again after a reconnect) once its part's deadline has
        passed becomes ``REJECT <id> late_link``: the part has moved on, and a PASS reaching the PLC now would pass
        a part nobody judged in time (or, resent, one whose first PASS the PLC may never have had)."""
        if p.deadline is not None and p.decision == Verdict.PASS and time.perf_counter() > p.deadline:
            p.line = decision_line(p.part_id, Verdict.REJECT, "late link")
            log.warning("PLC link %s: PASS %s not %s before its deadline: sent as REJECT", self.config.port,
                        p.part_id, "acknowledged" if p.sends else "sent")

    def _give_up(self, p: _Pending, why: str) -> None:
        text = p.line.decode().strip()
        self.stats.undelivered += 1
        log.error("PLC link %s: decision UNDELIVERED: %s (%s)", self.config.port, text, why)
        with self._lock:
            self._undelivered.append((p.part_id, text))
            self._outcomes.append((p.part_id, False, time.perf_counter(), p.decision))
        if self.on_undelivered is not None:
            self.on_undelivered(p.part_id, text)

    def _write(self, data: bytes) -> None:
        self._port.write(data)

    def _lost(self, exc: BaseException) -> None:
        self.stats.disconnects += 1
        self._link_up.clear()
        log.error("PLC link %s lost: %s; %d decision(s) pending", self.config.port, exc, self.pending())
        with self._lock:  # in-flight decisions may not have arrived: send them again after the reconnect
            again = sorted(self._inflight.values(), key=lambda p: p.sent_at or 0.0)
            self._inflight.clear()
            self._outbox.extendleft(reversed(again))
        self._close_port()

    def _reconnect(self) -> bool:
        for delay in backoff_delays_s(self.config.reconnect_backoff_s, self.config.reconnect_backoff_max_s, 2**31):
            if self._stop.wait(delay):
                return False
            try:
                self._port = self._factory(self.config)
            except (OSError, ValueError) as exc:
                log.debug("PLC link %s: reconnect failed: %s", self.config.port, exc)
                continue
            self.stats.reconnects += 1
            self._link_up.set()
            log.info("PLC link %s: reconnected; %d decision(s) to send", self.config.port, self.pending())
            return True
        return False

    def _close_port(self) -> None:
        port, self._port = self._port, None
        if port is not None:
            try:
                port.close()
            except (OSError, ValueError):
                pass

    def stats_snapshot(self) -> LineIOStats:
        return dataclasses.replace(self.stats)


def _open_serial(config: LineIOConfig) -> Any:
    import serial

    extra = {} if "://" in config.port else {"exclusive": True}  # a second opener of a real port is an error
    return serial.serial_for_url(config.port, baudrate=config.baudrate, timeout=min(config.timeout_ms, POLL_MS) / 1e3,
                                 write_timeout=config.timeout_ms / 1e3, **extra)
