"""``station bench faults``: its scoring of what the PLC saw against the log (fast), and two of its cases with the
real parts in private namespaces (slow)."""

from __future__ import annotations

import json
from pathlib import Path
from types import SimpleNamespace

import pytest

from station.benchmarks.faults import namespaces_unavailable_reason, score


def plc(decisions, acked=(), late=()):
    times = {p: 0.0 for p in decisions}
    return SimpleNamespace(record=SimpleNamespace(
        decisions=dict(decisions), trigger_times=times,
        decision_times={p: (1.0 if p in late else 0.05) for p in decisions}, acked=set(acked),
        triggers_sent=list(decisions)))


def test_fail_open_counts_passes_without_a_true_row_or_too_late():
    decisions = {"A": "PASS", "B": "PASS", "C": "PASS", "D": "REJECT x", "E": "PASS"}
    rows = [{"part_id": "A", "decision": "pass", "io_delivered": 1},
            {"part_id": "B", "decision": "reject", "io_delivered": 1},  # the row says reject, the PLC got PASS
            {"part_id": "D", "decision": "reject", "io_delivered": 0},
            {"part_id": "E", "decision": "pass", "io_delivered": 1}]
    r = score("x", [plc(decisions, acked={"A", "B", "D", "E"}, late={"E"})], rows,
              {"plc_link": {"triggers": 6}}, cycle_time_ms=300.0)
    # B: row not pass; C: no row; E: PASS 1 s after its trigger
    assert r.fail_open == 3 and r.rows == 4 and r.announced == 6 and r.unanswered == 1
    assert r.io_right == 3  # D has io_delivered 0 but the PLC acknowledged it


@pytest.mark.slow
def test_bench_faults_baseline_and_silent_plc(tmp_path: Path) -> None:
    why = namespaces_unavailable_reason()
    if why:
        pytest.skip(f"no private namespaces for the fault benchmark: {why}")
    from station.cli import main

    out = tmp_path / "faults"
    assert main(["bench", "faults", "--cases", "baseline,plc_silent", "--parts", "20", "--out", str(out)]) == 0
    cases = {c["case"]: c for c in json.loads((out / "faults.json").read_text())["cases"]}
    for c in cases.values():
        assert c["fail_open"] == 0 and c["unanswered"] == 0 and c["rows"] == c["announced"] == 20
        assert c["io_right"] == c["rows"]
    assert cases["plc_silent"]["acks"] == 10


@pytest.mark.slow
def test_bench_faults_camera_power_cycle(tmp_path: Path) -> None:
    """The camera killed and back at the same address 1 s later: the station reconnects and keeps running, every part
    announced answered with one row (those during the outage rejected), none passed unjudged."""
    why = namespaces_unavailable_reason()
    if why:
        pytest.skip(f"no private namespaces for the fault benchmark: {why}")
    from station.cli import main

    out = tmp_path / "faults"
    assert main(["bench", "faults", "--cases", "camera_power_cycle", "--parts", "30", "--out", str(out)]) == 0
    (c,) = json.loads((out / "faults.json").read_text())["cases"]
    assert c["fail_open"] == 0 and c["unanswered"] == 0 and c["rows"] == c["announced"] == 30
    assert c["extra"]["exit_code"] == 0 and c["extra"]["summary"]["camera"]["reconnects"] == 1
    assert c["passes"] < 30  # the parts announced while the camera was away were rejected
