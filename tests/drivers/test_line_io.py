"""The PLC line protocol over real pty pairs: socat (a peer that can disappear) and the in-process simulated PLC."""

from __future__ import annotations

import logging
import shutil
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
import serial

from drivers.errors import LineIOError
from drivers.line_io import LineIO, LineIOConfig, decision_line, reason_token
from drivers.plc_sim import SimulatedPLC

pytestmark = pytest.mark.skipif(shutil.which("socat") is None, reason="socat not installed")


class Socat:
    """``socat -d -d pty,raw,echo=0,link=A pty,raw,echo=0,link=B``: a pty pair with stable names."""

    def __init__(self, tmp: Path) -> None:
        self.a, self.b = str(tmp / "station"), str(tmp / "plc")
        self.proc: subprocess.Popen[bytes] | None = None

    def start(self) -> Socat:
        self.proc = subprocess.Popen(["socat", "-d", "-d", f"pty,raw,echo=0,link={self.a}",
                                      f"pty,raw,echo=0,link={self.b}"], stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 5
        while not (Path(self.a).exists() and Path(self.b).exists()):
            assert time.monotonic() < deadline, "socat did not create its ptys"
            time.sleep(0.01)
        return self

    def kill(self) -> None:
        if self.proc and self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        for p in (self.a, self.b):  # socat leaves dangling links when killed
            Path(p).unlink(missing_ok=True)


class Peer:
    """The test's end (PLC side) of the socat pair."""

    def __init__(self, path: str) -> None:
        self.s = serial.Serial(path, timeout=0.05)
        self.buf = b""

    def send(self, data: bytes) -> None:
        self.s.write(data)

    def lines(self, n: int, timeout_s: float = 3.0, skip_hb: bool = True) -> list[str]:
        out: list[str] = []
        deadline = time.monotonic() + timeout_s
        while len(out) < n and time.monotonic() < deadline:
            self.buf += self.s.read(256)
            while b"\n" in self.buf and len(out) < n:
                line, self.buf = self.buf.split(b"\n", 1)
                if not (skip_hb and line == b"HB"):
                    out.append(line.decode())
        return out

    def close(self) -> None:
        self.s.close()


@pytest.fixture
def pair(tmp_path: Path) -> Iterator[Socat]:
    s = Socat(tmp_path).start()
    yield s
    s.kill()


def cfg(port: str, **kw: object) -> LineIOConfig:
    base: dict[str, object] = dict(heartbeat_s=0.0, ack_timeout_ms=500, reconnect_backoff_s=0.05,
                                   reconnect_backoff_max_s=0.2, timeout_ms=200)
    base.update(kw)
    return LineIOConfig(port=port, **base)  # type: ignore[arg-type]


def test_lines_are_well_formed() -> None:
    assert decision_line("P-17", "pass", None) == b"PASS P-17\n"
    assert decision_line("17", "reject", "NaN score (model)") == b"REJECT 17 nan_score_model\n"
    assert decision_line("17", "not_inspected", None) == b"REJECT 17 rejected\n"  # fail closed
    assert len(reason_token("x" * 100)) == 24
    with pytest.raises(LineIOError, match="part id 'a b'"):
        decision_line("a b", "pass", None)


def test_trigger_decision_ack_round_trip(pair: Socat) -> None:
    peer = Peer(pair.b)
    with LineIO(cfg(pair.a)) as io:
        peer.send(b"TRIG 17\r\nTRIG 18\n")
        assert io.next_trigger(2.0).part_id == "17" and io.next_trigger(2.0).part_id == "18"
        assert io.report("17", "pass", None) is False  # pending until acknowledged
        assert io.report("18", "reject", "anomaly score 0.93") is False
        assert peer.lines(2) == ["PASS 17", "REJECT 18 anomaly_score_0_93"]
        assert io.pending() == 2 and io.outcomes() == []  # until the PLC acknowledges
        peer.send(b"ACK 17\nACK 18\n")
        assert io.flush(2.0)
        assert [o[:2] for o in io.outcomes()] == [("17", True), ("18", True)] and io.outcomes() == []
        assert io.next_trigger(0.05) is None
    assert io.undelivered() == [] and io.stats.acked == 2
    peer.close()


def test_faults_are_logged_counted_and_answered(pair: Socat, caplog: pytest.LogCaptureFixture) -> None:
    peer = Peer(pair.b)
    caplog.set_level(logging.WARNING, "drivers.line_io")
    with LineIO(cfg(pair.a)) as io:
        peer.send(b"\xff\xfe garbage\n")
        peer.send(b"A" * 200 + b"\n")  # over-long: dropped up to its newline
        peer.send(b"FOO 1\n")
        peer.send(b"TRIG bad id!\n")
        peer.send(b"TRIG 5\nTRIG 5\n")
        peer.send(b"ERR conveyor jam\n")
        assert io.next_trigger(2.0).part_id == "5"
        errs = peer.lines(5)
        assert io.next_trigger(0.2) is None  # the duplicate never becomes a part
    assert errs == ["ERR not ASCII", "ERR line over 64 bytes", "ERR unknown command 'FOO'", "ERR bad part id",
                    "ERR duplicate id 5"]
    s = io.stats
    assert (s.garbage, s.too_long, s.unknown, s.duplicates, s.plc_errors, s.triggers) == (2, 1, 1, 1, 1, 1)
    assert "duplicate trigger id '5'" in caplog.text and "over 64 bytes" in caplog.text
    peer.close()


def test_peer_disappears_decisions_wait_and_go_out_after_reconnect(pair: Socat,
                                                                   caplog: pytest.LogCaptureFixture) -> None:
    peer = Peer(pair.b)
    io = LineIO(cfg(pair.a))
    io.start()
    peer.send(b"TRIG 1\n")
    assert io.next_trigger(2.0).part_id == "1"
    peer.close()
    pair.kill()  # the PLC side vanishes
    deadline = time.monotonic() + 3
    while io.link_up and time.monotonic() < deadline:
        time.sleep(0.01)
    assert not io.link_up
    assert io.report("1", "reject", "anomaly") is False  # queued, not lost
    assert io.report("2", "pass", None) is False
    pair.start()
    peer = Peer(pair.b)
    got = peer.lines(2, timeout_s=5)
    assert got == ["REJECT 1 anomaly", "PASS 2"]
    peer.send(b"ACK 1\nACK 2\n")
    assert io.flush(2.0)
    assert [o[:2] for o in io.outcomes()] == [("1", True), ("2", True)]  # acknowledged after the reconnect
    assert io.close() == []
    assert io.stats.disconnects >= 1 and io.stats.reconnects >= 1
    assert "PLC link" in caplog.text and "lost" in caplog.text
    peer.close()


def test_unacknowledged_and_closed_while_down_are_reported_undelivered(pair: Socat) -> None:
    peer = Peer(pair.b)
    reported: list[tuple[str, str]] = []
    io = LineIO(cfg(pair.a, ack_timeout_ms=100, max_resends=1), on_undelivered=lambda *a: reported.append(a))
    io.start()
    io.report("9", "pass", None)
    assert peer.lines(2, timeout_s=2) == ["PASS 9", "PASS 9"]  # sent, then resent once
    deadline = time.monotonic() + 2
    while not reported and time.monotonic() < deadline:
        time.sleep(0.01)
    assert reported == [("9", "PASS 9")]
    peer.close()
    pair.kill()
    time.sleep(0.3)
    io.report("10", "reject", "timeout")
    left = io.close(flush_timeout_s=0.2)
    assert left == [("9", "PASS 9"), ("10", "REJECT 10 timeout")] and io.stats.undelivered == 2
    assert [o[:2] for o in io.outcomes()] == [("9", False), ("10", False)]  # never acknowledged: not delivered


def test_station_heartbeat(pair: Socat) -> None:
    peer = Peer(pair.b)
    with LineIO(cfg(pair.a, heartbeat_s=0.1)):
        assert peer.lines(2, timeout_s=2, skip_hb=False) == ["HB", "HB"]
    peer.close()


def test_trigger_free_mode_ignores_triggers_but_reports(pair: Socat) -> None:
    peer = Peer(pair.b)
    with LineIO(cfg(pair.a, triggered=False, require_ack=False)) as io:
        assert io.triggered is False
        peer.send(b"TRIG 3\n")
        assert io.next_trigger(0.3) is None
        io.report("free-1", "pass", None)
        assert peer.lines(1) == ["PASS free-1"]
        assert io.flush(1.0)
    peer.close()


def test_bad_port_is_a_clear_error(tmp_path: Path) -> None:
    with pytest.raises(LineIOError, match=r"PLC port '.*/nope': cannot open"):
        LineIO(cfg(str(tmp_path / "nope"))).start()


def test_with_the_simulated_plc() -> None:
    with SimulatedPLC(trigger_period_s=0.01, heartbeat_s=0.05) as plc:
        assert plc.station_port is not None
        with LineIO(cfg(plc.station_port, heartbeat_s=0.05)) as io:
            ids = []
            while len(ids) < 20:
                trigger = io.next_trigger(2.0)
                assert trigger is not None
                part = trigger.part_id
                ids.append(part)
                io.report(part, "pass" if len(ids) % 3 else "reject", "anomaly")
            assert io.flush(3.0)
        assert plc.wait_decisions(20, 2.0)
    assert ids == [f"P{i}" for i in range(1, 21)]
    assert plc.record.decisions["P3"] == "REJECT anomaly" and plc.record.decisions["P1"] == "PASS"
    assert plc.record.duplicate_decisions == 0 and io.undelivered() == [] and plc.record.heartbeats >= 1


def test_triggers_carry_their_arrival_time_and_stale_ones_can_be_taken_out(pair: Socat) -> None:
    peer = Peer(pair.b)
    with LineIO(cfg(pair.a)) as io:
        t0 = time.perf_counter()
        peer.send(b"TRIG a1\nTRIG a2\n")
        deadline = time.monotonic() + 2
        while io.stats.triggers < 2 and time.monotonic() < deadline:
            time.sleep(0.005)
        time.sleep(0.3)  # the station is busy elsewhere: the triggers age in the queue
        first = io.expired(before=time.perf_counter() - 0.2)
        assert [t.part_id for t in first] == ["a1", "a2"]
        assert all(t0 <= t.t_arrival <= t0 + 0.2 for t in first)  # when they reached the host, not when taken
        assert io.next_trigger(0.05) is None
    peer.close()


def test_refusing_triggers_answers_waiting_and_new_ones_with_a_reason(pair: Socat) -> None:
    peer = Peer(pair.b)
    seen: list[str] = []
    with LineIO(cfg(pair.a)) as io:
        peer.send(b"TRIG w1\n")
        deadline = time.monotonic() + 2
        while io.stats.triggers < 1 and time.monotonic() < deadline:
            time.sleep(0.005)
        io.refuse_triggers(lambda t: seen.append(t.part_id) or "station stopping")
        peer.send(b"TRIG n1\n")
        assert peer.lines(2) == ["REJECT w1 station_stopping", "REJECT n1 station_stopping"]
        assert seen == ["w1", "n1"] and io.next_trigger(0.05) is None
        peer.send(b"ACK w1\nACK n1\n")
        assert io.flush(2.0)
    peer.close()


def test_a_pass_that_cannot_go_out_before_its_deadline_goes_out_as_a_reject(pair: Socat) -> None:
    """A PASS queued while the link was down reached the PLC seconds later, after the part had moved on."""
    peer = Peer(pair.b)
    with LineIO(cfg(pair.a)) as io:
        io.report("7", "pass", None, deadline=time.perf_counter() - 0.5)  # already too late to pass
        io.report("8", "pass", None, deadline=time.perf_counter() + 60)
        assert peer.lines(2) == ["REJECT 7 late_link", "PASS 8"]
        peer.send(b"ACK 7\nACK 8\n")
        assert io.flush(2.0)
        assert [(p, ok, sent) for p, ok, _, sent in io.outcomes()] == [("7", True, "reject"), ("8", True, "pass")]
    peer.close()


def test_a_pass_unacknowledged_by_its_deadline_is_never_sent_again_as_a_pass(pair: Socat) -> None:
    """A PASS the PLC did not acknowledge is resent; once its part's deadline has passed, a resend as PASS would reach
    the PLC after the part moved on (fail open): it goes out as REJECT late_link, and the outcome says reject."""
    peer = Peer(pair.b)
    with LineIO(cfg(pair.a, ack_timeout_ms=200, max_resends=3)) as io:
        io.report("11", "pass", None, deadline=time.perf_counter() + 0.1)
        assert peer.lines(2, timeout_s=2) == ["PASS 11", "REJECT 11 late_link"]  # the ACK of the PASS never came
        peer.send(b"ACK 11\n")
        assert io.flush(2.0)
        assert [(p, ok, sent) for p, ok, _, sent in io.outcomes()] == [("11", True, "reject")]
    peer.close()


def test_a_pass_in_flight_when_the_link_drops_is_not_resent_as_a_pass_after_its_deadline(pair: Socat) -> None:
    """Decisions in flight when the link drops are sent again after the reconnect; a PASS whose deadline passed
    meanwhile goes out as REJECT late_link."""
    peer = Peer(pair.b)
    with LineIO(cfg(pair.a, ack_timeout_ms=5000)) as io:
        io.report("12", "pass", None, deadline=time.perf_counter() + 0.2)
        assert peer.lines(1) == ["PASS 12"]
        peer.close()
        pair.kill()
        deadline = time.monotonic() + 3
        while io.link_up and time.monotonic() < deadline:
            time.sleep(0.01)
        assert not io.link_up
        time.sleep(0.3)  # down past the part's deadline
        pair.start()
        peer = Peer(pair.b)
        assert peer.lines(1, timeout_s=5) == ["REJECT 12 late_link"]
        peer.send(b"ACK 12\n")
        assert io.flush(2.0)
        assert [(p, ok, sent) for p, ok, _, sent in io.outcomes()] == [("12", True, "reject")]
    peer.close()


def test_an_id_reused_after_the_duplicate_window_is_a_new_part(pair: Socat) -> None:
    """A PLC whose counter restarted (a power cycle) announces ids it used before: each is a new part, answered and
    logged. Every such part used to get "ERR duplicate id" and no row, until 4096 other ids had passed."""
    peer = Peer(pair.b)
    with LineIO(cfg(pair.a, duplicate_window_s=0.3)) as io:
        peer.send(b"TRIG 1\n")
        assert io.next_trigger(2.0).part_id == "1"
        peer.send(b"TRIG 1\n")  # at once: the same part announced again
        assert peer.lines(1) == ["ERR duplicate id 1"] and io.next_trigger(0.1) is None
        time.sleep(0.4)
        peer.send(b"TRIG 1\n")  # later: another part with the same id
        assert io.next_trigger(2.0).part_id == "1"
    assert (io.stats.triggers, io.stats.duplicates) == (2, 1)
    peer.close()


def test_a_simulated_plc_that_has_sent_its_parts_waits_instead_of_spinning() -> None:
    """Once ``max_triggers`` parts are out, the PLC only beats its heart and listens. Its wait used to count the next
    trigger time, left in the past, so it polled its port without pause and took a whole core (100 % for minutes in a
    hung test run, 2026-11-29), on a machine whose 2 cores the station under test needs."""
    with SimulatedPLC(trigger_period_s=0.01, heartbeat_s=0.2, max_triggers=2) as plc:
        time.sleep(0.1)  # both parts out
        reads = 0
        read = plc._transport.read

        def counted(timeout_s: float) -> bytes:
            nonlocal reads
            reads += 1
            return read(timeout_s)

        plc._transport.read = counted
        time.sleep(0.5)
    assert plc.record.triggers_sent == ["P1", "P2"]
    assert reads <= 30, reads  # about one per 50 ms (0.5 s); spinning made tens of thousands


def test_closing_the_simulated_plc_twice_leaves_file_numbers_reused_since_alone() -> None:
    import os

    plc = SimulatedPLC(trigger_period_s=None, heartbeat_s=0.05).start()
    plc.close()
    r, w = os.pipe()  # the lowest free numbers: those the PLC's pty pair just gave back
    try:
        plc.close()  # a second close (an exit stack and a finally, say) must not close the pipe
        os.write(w, b"x")
        assert os.read(r, 1) == b"x"
    finally:
        os.close(r)
        os.close(w)


def test_the_simulated_plc_keeps_its_port_open_while_its_thread_is_stuck_in_a_write() -> None:
    import os
    import threading

    plc = SimulatedPLC(trigger_period_s=None, heartbeat_s=0.01)
    release, entered = threading.Event(), threading.Event()

    def stuck(data: bytes) -> None:  # a write blocked on a station that no longer reads
        entered.set()
        release.wait()

    plc._transport.write = stuck
    plc.start()
    assert entered.wait(2)
    fd = plc._transport.fd
    plc.close()  # gives up on the thread after 2 s
    os.fstat(fd)  # still open: the thread may still read it
    release.set()
    plc._thread.join(2)
    plc.close()
    with pytest.raises(OSError):
        os.fstat(fd)
