"""The SQLite inspection log: durability, faults named, retention, streaming export in three formats."""

from __future__ import annotations

import csv
import json
import signal
import subprocess
import sys
import textwrap
from collections import Counter
from pathlib import Path

import pytest

from station.inspection_log import (
    ADDED_IN_VERSION,
    COLUMNS,
    SCHEMA_VERSION,
    InspectionLog,
    InspectionRecord,
    LogError,
    export_rows,
)

ROOT = Path(__file__).resolve().parents[2]

def rec(i: int, decision: str = "pass", **kw) -> InspectionRecord:
    return InspectionRecord(decision=decision, time_unix_s=1000.0 + i, part_id=f"P{i}", camera_frame_id=i,
                            score=0.1 * (i % 10), threshold=0.5, total_ms=12.5, io_delivered=True, **kw)


def test_committed_rows_survive_a_killed_writer(tmp_path):
    db = tmp_path / "log.sqlite"
    script = textwrap.dedent(f"""
        import os, signal, sys
        from station.inspection_log import InspectionLog, InspectionRecord
        log = InspectionLog({str(db)!r})
        for i in range(50):
            log.append(InspectionRecord(decision="pass", time_unix_s=float(i)))
        print("appended", flush=True)
        os.kill(os.getpid(), signal.SIGKILL)
    """)
    r = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True)
    assert r.returncode == -signal.SIGKILL and "appended" in r.stdout
    with InspectionLog(db, readonly=True) as log:
        assert log.count() == 50


def test_full_disk_is_a_clear_error_and_loses_no_committed_row(tmp_path):
    log = InspectionLog(tmp_path / "log.sqlite")
    log.append([rec(i) for i in range(5)])
    pages = log._db.execute("PRAGMA page_count").fetchone()[0]
    log._db.execute(f"PRAGMA max_page_count={pages}")  # SQLite's own SQLITE_FULL path, as on a full disk
    with pytest.raises(LogError, match=r"log\.sqlite: cannot write 500 record\(s\).*full"):
        log.append([rec(i, reason="x" * 1000) for i in range(500)])
    assert log.count() == 5


def test_unwritable_location_is_named(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    with pytest.raises(LogError, match=r"file/log\.sqlite: cannot open"):
        InspectionLog(blocker / "log.sqlite")
    with pytest.raises(LogError, match="no such file"):
        InspectionLog(tmp_path / "missing.sqlite", readonly=True)


def test_bad_decision_is_refused():
    with pytest.raises(ValueError, match="decision"):
        InspectionRecord(decision="maybe", time_unix_s=0.0)


def test_filters_and_retention(tmp_path):
    with InspectionLog(tmp_path / "log.sqlite") as log:
        log.append([rec(i, "reject" if i % 3 == 0 else "pass", image_path=f"img{i}.png") for i in range(30)])
        assert log.count("reject") == 10
        rows = list(log.rows(since_unix_s=1010, until_unix_s=1020, decision="reject", batch_size=2))
        assert [r["part_id"] for r in rows] == ["P12", "P15", "P18"]
        removed = log.apply_retention(retention_days=1, now_unix_s=1010.0 + 86400)
        assert removed == [f"img{i}.png" for i in range(10)]
        assert log.count() == 20
        assert log.apply_retention(0) == [] and log.count() == 20


@pytest.mark.parametrize("fmt", ["csv", "jsonl", "parquet"])
def test_export_round_trips_every_column(tmp_path, fmt):
    out = tmp_path / f"export.{fmt}"
    with InspectionLog(tmp_path / "log.sqlite") as log:
        log.append([rec(i, "reject" if i == 3 else "pass", reason="score above threshold" if i == 3 else None)
                    for i in range(7)])
        n = export_rows(log.rows(batch_size=3), out, fmt, batch_size=2)
    assert n == 7 and not (tmp_path / f"export.{fmt}.partial").exists()
    if fmt == "csv":
        rows = list(csv.DictReader(out.open()))
    elif fmt == "jsonl":
        rows = [json.loads(line) for line in out.read_text().splitlines()]
    else:
        import pyarrow.parquet as pq
        rows = pq.read_table(out).to_pylist()
    assert list(rows[0]) == ["id", *COLUMNS]
    assert [r["decision"] for r in rows].count("reject") == 1
    assert rows[3]["reason"] == "score above threshold" and rows[3]["part_id"] == "P3"


FULL = InspectionRecord(
    decision="reject", time_unix_s=1000.5, part_id="P9", camera_frame_id=9, camera_timestamp_ns=123456789,
    score=0.7, threshold=0.5, model_id="m1", reason="score 0.7000 > threshold 0.5000", grab_ms=1.0, demosaic_ms=2.0,
    priors_ms=3.0, model_ms=4.0, decision_ms=0.1, io_ms=5.0, total_ms=15.0, io_delivered=True, ground_truth_label=1,
    ground_truth_present=True, image_path="img/9.png", median_level=0.4, high_level=0.8, clipped_fraction=0.01,
    dolp_level=0.05, drift="brighter", highlight_fraction=0.02, noise_level=1.1, second_score=0.3,
    second_threshold=0.6, second_model_id="side1", second_frame_id=11, edge_bend=-1.5,
    edge_step=2.5, unseen_fraction=0.03, turn_deg=-7.5, look_level=0.31)
"""A record with every column set (a two-camera station's row: its second model's id is text)."""


@pytest.mark.parametrize("fmt", ["csv", "jsonl", "parquet"])
def test_export_keeps_each_columns_value_and_type(tmp_path, fmt):
    assert all(getattr(FULL, c) is not None for c in COLUMNS)  # a column added later must be set here too
    out = tmp_path / f"export.{fmt}"
    with InspectionLog(tmp_path / "log.sqlite") as log:
        log.append(FULL)
        assert export_rows(log.rows(), out, fmt) == 1
    if fmt == "csv":
        row = next(csv.DictReader(out.open()))
        assert {c: row[c] for c in COLUMNS} == {c: str(getattr(FULL, c)) for c in COLUMNS}
        return
    if fmt == "jsonl":
        row = json.loads(out.read_text())
    else:
        import pyarrow.parquet as pq
        row = pq.read_table(out).to_pylist()[0]
    assert {c: row[c] for c in COLUMNS} == {c: getattr(FULL, c) for c in COLUMNS}


def test_export_log_cli(tmp_path):
    db = tmp_path / "log.sqlite"
    with InspectionLog(db) as log:
        log.append([rec(i, "reject" if i % 2 else "pass") for i in range(6)])
    out = tmp_path / "rejects.jsonl"
    r = subprocess.run([sys.executable, "-m", "station.cli", "export-log", "--db", str(db), "--decision", "reject",
                        "--since", "1001", "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert [json.loads(x)["part_id"] for x in out.read_text().splitlines()] == ["P1", "P3", "P5"]
    bad = subprocess.run([sys.executable, "-m", "station.cli", "export-log", "--db", str(tmp_path / "none.sqlite"),
                          "--out", str(out)], capture_output=True, text=True)
    assert bad.returncode == 2 and "none.sqlite: no such file" in bad.stderr and "Traceback" not in bad.stderr


def test_report_counts_rates_latency_and_confusion(tmp_path):
    from station.log_report import summarize

    rows = [rec(i, "reject" if i < 3 else "pass", ground_truth_label=int(i < 2)) for i in range(10)]
    rows.append(InspectionRecord(decision="not_inspected", time_unix_s=2000.0, reason="queue full"))
    with InspectionLog(tmp_path / "log.sqlite") as log:
        log.append(rows)
        s = summarize(log.rows())
    assert s.counts == {"pass": 7, "reject": 3, "empty": 0, "not_inspected": 1}
    assert s.reject_rate == pytest.approx(0.3)
    assert s.latency_ms["p50"] == pytest.approx(12.5)
    assert s.confusion == {"bad_reject": 2, "good_reject": 1, "good_pass": 7}
    assert sum(s.score_hist["pass"]) == 7 and sum(s.score_hist["reject"]) == 3


def test_report_tells_how_many_parts_were_judged_under_a_drift_warning(tmp_path):
    from station.log_report import format_summary, summarize

    warn = "drift over the last 50 frames: median_level 0.120 outside trained 0.400..0.500 (frames darker ...)"
    with InspectionLog(tmp_path / "log.sqlite") as log:
        log.append([rec(i, median_level=0.45, drift=None) for i in range(5)]
                   + [rec(i, median_level=0.12, drift=warn) for i in range(5, 8)])
        s = summarize(log.rows())
    assert s.drift_parts == 3 and s.last_drift == warn
    assert "DRIFT: 3 part(s)" in format_summary(s)


def test_report_gives_the_models_frame_checks_and_warns_of_a_noisy_line(tmp_path):
    from station.log_report import format_summary, summarize

    with InspectionLog(tmp_path / "log.sqlite") as log:
        log.append([rec(i, noise_level=1.0 + 0.01 * i, highlight_fraction=0.02) for i in range(10)] + [rec(10)])
        quiet = summarize(log.rows())
        log.append([rec(i, noise_level=2.0, highlight_fraction=0.0) for i in range(11, 31)])
        noisy = summarize(log.rows())
    assert quiet.frame_checks["noise_level"]["max"] == pytest.approx(1.09)  # the row without checks is left out
    assert quiet.frame_checks["highlight_fraction"]["median"] == pytest.approx(0.02)
    assert "noise_level: median 1.045" in format_summary(quiet) and "NOISE" not in format_summary(quiet)
    assert "NOISE: the frames' median noise level is 2.00" in format_summary(noisy)


def test_report_gives_the_size_of_the_edge_bend_which_bends_either_way(tmp_path):
    """A part bent the other way has a negative bend: its max over parts read the least bent part, not the most."""
    from station.log_report import format_summary, summarize

    with InspectionLog(tmp_path / "log.sqlite") as log:
        log.append([rec(i, edge_bend=b) for i, b in enumerate((0.1, -0.2, 0.3, -6.5))])
        s = summarize(log.rows())
    assert s.frame_checks["edge_bend"]["max"] == pytest.approx(6.5)
    assert "|edge_bend|: median 0.250" in format_summary(s)


def test_report_warns_when_more_than_a_few_parts_lay_partly_outside_the_models_view(tmp_path):
    """A camera turned from square puts some of many parts outside the model's view; a square line a few (0.7-1.7 %
    of the parts of two development sets). The report warns over ``VIEW_WARN_SHARE`` of the parts with the column,
    once ``VIEW_WARN_MIN_PARTS`` have it; a reject's cause is what else its reason says."""
    from model.draem.frame_checks import beyond_limits
    from station.drift import VIEW_WARN_MIN_PARTS
    from station.log_report import format_summary, reject_cause, summarize

    n = 120
    few = [0.002 if i in (0, 7, 30) else 0.0 for i in range(n)]  # 3 of 120: a square line's share
    many = [0.002 if i % 8 == 0 else 0.0 for i in range(n)]  # 15 of 120: 12.5 %
    with InspectionLog(tmp_path / "log.sqlite") as log:
        log.append([rec(i, unseen_fraction=u) for i, u in enumerate(few)] + [rec(n)])
        square = summarize(log.rows())
    with InspectionLog(tmp_path / "turned.sqlite") as log:
        log.append([rec(i, unseen_fraction=u) for i, u in enumerate(many)])
        turned = summarize(log.rows())
        early = summarize(list(log.rows())[:VIEW_WARN_MIN_PARTS - 1])
    assert (square.outside_view_parts, square.view_parts) == (3, n)  # the row without the column left out
    assert "VIEW" not in format_summary(square)
    assert "VIEW: 15 of 120 parts lay partly outside the model's view" in format_summary(turned)
    assert early.outside_view_parts == 13 and "VIEW" not in format_summary(early)  # too few parts to tell a line
    assert turned.frame_checks["unseen_fraction"]["max"] == pytest.approx(0.002)
    both = "; ".join(["score 0.99 > threshold 0.98", *beyond_limits({"edge_bend": 3.0, "unseen_fraction": 0.002})])
    assert reject_cause(both) == "part bent (shape check)"


def test_report_warns_when_the_parts_lie_turned_from_the_models_good_parts(tmp_path):
    """A camera turned from square moves every part's ``turn_deg`` (about -7.5 degrees turned 8, seed 1219); a square
    line's parts spread about 0. The report says TURN once the median of at least ``TURN_WARN_MIN_PARTS`` parts with
    the column is beyond ``TURN_WARN_DEG``; a reject whose reason names a part turned beyond the limit counts as
    "part turned", before the shape check its turned edges also tripped."""
    from model.draem.frame_checks import beyond_limits
    from station.drift import TURN_WARN_MIN_PARTS
    from station.log_report import format_summary, reject_cause, summarize

    square = [(-5.0 + 10.0 * i / 119) for i in range(120)]
    with InspectionLog(tmp_path / "square.sqlite") as log:
        log.append([rec(i, turn_deg=t) for i, t in enumerate(square)] + [rec(120)])
        flat = summarize(log.rows())
    with InspectionLog(tmp_path / "turned.sqlite") as log:
        log.append([rec(i, turn_deg=t - 7.5) for i, t in enumerate(square)])
        turned = summarize(log.rows())
        early = summarize(list(log.rows())[:TURN_WARN_MIN_PARTS - 1])
    assert flat.turn_median_deg is None and "TURN" not in format_summary(flat)
    assert turned.turn_median_deg == pytest.approx(-7.5) and turned.turn_parts == 120
    assert ("TURN: the 120 parts lay turned -7.5 degrees from the model's good parts at the median (beyond 5): the "
            "camera turned from square") in format_summary(turned)
    assert early.turn_median_deg is None  # too few parts to tell a line
    assert turned.frame_checks["turn_deg"]["max"] == pytest.approx(12.5)  # of its size
    both = "; ".join(["score 0.99 > threshold 0.98", *beyond_limits({"edge_bend": 3.0, "turn_deg": -26.0})])
    assert reject_cause(both) == "part turned"


def test_report_warns_when_the_look_network_reads_the_parts_as_unlike_its_renders(tmp_path):
    """A lens the renders did not have raises the good parts' ``look_level`` (median 0.27 on the renders, 0.53 through
    a vignetting lens, seed 1240). The report says LOOK once the median of at least ``LOOK_WARN_MIN_PARTS`` parts with
    the column is above ``LOOK_WARN_LEVEL``; a log from a file without the blend has none and says nothing."""
    from station.drift import LOOK_WARN_MIN_PARTS
    from station.log_report import format_summary, summarize

    renders = [0.1 + 0.35 * i / 119 for i in range(120)]
    with InspectionLog(tmp_path / "renders.sqlite") as log:
        log.append([rec(i, look_level=v) for i, v in enumerate(renders)] + [rec(120)])
        quiet = summarize(log.rows())
    with InspectionLog(tmp_path / "lens.sqlite") as log:
        log.append([rec(i, look_level=v + 0.26) for i, v in enumerate(renders)])
        lens = summarize(log.rows())
        early = summarize(list(log.rows())[:LOOK_WARN_MIN_PARTS - 1])
    assert quiet.look_median is None and "LOOK" not in format_summary(quiet)
    assert lens.look_median == pytest.approx(0.535) and lens.look_parts == 120
    assert ("LOOK: the 120 parts' look level is 0.54 at the median (above 0.4): the look network reads these frames "
            "as unlike its renders") in format_summary(lens)
    assert early.look_median is None  # too few parts to tell a line


def test_the_log_has_a_column_for_every_frame_check_the_model_reports():
    from model.draem.frame_checks import FRAME_CHECKS

    assert set(FRAME_CHECKS) <= set(COLUMNS)


def test_the_log_and_its_report_import_without_torch():
    """A station reading or reporting its log must not load the model: the frame checks come from a torch-free
    module."""
    code = ("import sys; import station.inspection_log, station.log_report; "
            "assert 'torch' not in sys.modules, 'torch imported'")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_report_cli_writes_json_and_png(tmp_path):
    db = tmp_path / "log.sqlite"
    with InspectionLog(db) as log:
        log.append([rec(i, "reject" if i % 4 == 0 else "pass") for i in range(20)])
    r = subprocess.run([sys.executable, "-m", "station.cli", "report", "--db", str(db), "--out", str(tmp_path / "r")],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "reject rate (of judged parts): 25.00 %" in r.stdout
    assert json.loads((tmp_path / "r" / "report.json").read_text())["counts"]["reject"] == 5
    assert (tmp_path / "r" / "report.png").read_bytes()[:4] == b"\x89PNG"


V1_COLUMNS = [c for c in COLUMNS if not any(c in cols for cols in ADDED_IN_VERSION.values())]


def _v1_log(path) -> None:
    """A log as schema version 1 wrote it (no ground_truth_present column), with two rows."""
    import sqlite3

    cols = ", ".join(f"{c} {'TEXT' if c in ('decision', 'part_id', 'model_id', 'reason', 'image_path') else 'REAL'}"
                     for c in V1_COLUMNS)
    db = sqlite3.connect(path)
    db.execute(f"CREATE TABLE inspections (id INTEGER PRIMARY KEY AUTOINCREMENT, {cols})")
    for i in range(2):
        db.execute(f"INSERT INTO inspections (decision, time_unix_s, part_id, ground_truth_label) "
                   f"VALUES ('pass', {1000.0 + i}, 'old{i}', 0)")
    db.execute("PRAGMA user_version=1")
    db.commit()
    db.close()


def test_version_1_log_reads_and_is_migrated_on_write(tmp_path):
    db = tmp_path / "v1.sqlite"
    _v1_log(db)
    with InspectionLog(db, readonly=True) as log:  # read-only: the old file is not touched
        rows = list(log.rows())
    assert [r["part_id"] for r in rows] == ["old0", "old1"] and all(r["ground_truth_present"] is None for r in rows)
    out = tmp_path / "v1.csv"
    with InspectionLog(db, readonly=True) as log:
        assert export_rows(log.rows(), out, "csv") == 2
    assert next(csv.DictReader(out.open())).keys() == {"id", *COLUMNS}
    with InspectionLog(db) as log:  # writing adds the column; old rows keep their values
        log.append(rec(5, "empty", ground_truth_present=False))
        rows = list(log.rows())
    assert [r["part_id"] for r in rows] == ["old0", "old1", "P5"]
    assert [r["ground_truth_present"] for r in rows] == [None, None, False]
    assert rows[0]["ground_truth_label"] == 0
    import sqlite3

    assert sqlite3.connect(db).execute("PRAGMA user_version").fetchone()[0] == SCHEMA_VERSION


def test_newer_schema_is_refused_by_name(tmp_path):
    import sqlite3

    db = tmp_path / "v11.sqlite"
    con = sqlite3.connect(db)
    con.execute("PRAGMA user_version=11")
    con.close()
    with pytest.raises(LogError, match=r"v11\.sqlite: schema version 11"):
        InspectionLog(db, readonly=True)


def test_report_scores_the_presence_check_on_empty_views(tmp_path):
    from station.log_report import format_summary, summarize

    rows = [rec(0, "empty", ground_truth_present=False), rec(1, "pass", ground_truth_present=False),
            rec(2, "empty", ground_truth_label=1, ground_truth_present=True),
            rec(3, "pass", ground_truth_label=0, ground_truth_present=True)]
    with InspectionLog(tmp_path / "log.sqlite") as log:
        log.append(rows)
        s = summarize(log.rows())
    assert s.confusion == {"none_empty": 1, "none_pass": 1, "bad_empty": 1, "good_pass": 1}
    text = format_summary(s)
    assert "1 logged empty, 1 judged as a part" in text and "of which 1 showed a part" in text


@pytest.mark.parametrize("kind", ["other tables", "version 99", "other columns"])
def test_a_foreign_sqlite_file_is_refused_before_anything_in_it_changes(tmp_path, kind):
    import hashlib
    import sqlite3

    db = tmp_path / "foreign.sqlite"
    con = sqlite3.connect(db)
    if kind == "other tables":
        con.execute("CREATE TABLE orders (id INTEGER PRIMARY KEY, customer TEXT)")
    elif kind == "version 99":
        con.execute("CREATE TABLE inspections (id INTEGER PRIMARY KEY, decision TEXT)")
        con.execute("PRAGMA user_version=99")
    else:
        con.execute("CREATE TABLE inspections (id INTEGER PRIMARY KEY, decision TEXT, colour TEXT)")
    con.commit()
    con.close()
    before = hashlib.sha256(db.read_bytes()).hexdigest()
    with pytest.raises(LogError, match=r"foreign\.sqlite: .*file left as it was"):
        InspectionLog(db)
    assert hashlib.sha256(db.read_bytes()).hexdigest() == before
    assert not (tmp_path / "foreign.sqlite-wal").exists()
    assert sqlite3.connect(db).execute("PRAGMA journal_mode").fetchone()[0] == "delete"


def test_io_delivered_is_set_by_row_id_after_the_row_is_written(tmp_path):
    with InspectionLog(tmp_path / "log.sqlite") as log:
        ids = log.append([InspectionRecord("pass", 1000.0 + i, io_delivered=False) for i in range(3)])
        assert ids == [1, 2, 3]
        log.set_delivered({1: (True, 3.5), 3: (True, 1.0)})
        assert [(r["io_delivered"], r["io_ms"]) for r in log.rows()] == [(True, 3.5), (False, None), (True, 1.0)]


def test_the_write_ahead_log_stays_small(tmp_path):
    with InspectionLog(tmp_path / "log.sqlite") as log:
        for i in range(3000):
            log.append(rec(i, reason="x" * 200))
        wal = tmp_path / "log.sqlite-wal"
        assert wal.stat().st_size < 600 * 1024  # SQLite's default lets it grow to ~4 MB


@pytest.mark.parametrize("fmt", ["csv", "jsonl"])
def test_verdicts_are_stored_and_exported_as_the_plain_strings(tmp_path, fmt):
    import sqlite3

    from station.decision import Verdict

    files = []
    for kind, decisions in (("str", ("pass", "reject", "empty", "not_inspected")), ("enum", tuple(Verdict))):
        with InspectionLog(tmp_path / f"{kind}.sqlite") as log:
            log.append([rec(i, d) for i, d in enumerate(decisions)])
            assert all(r.decision is v for r, v in zip([rec(0, d) for d in decisions], Verdict, strict=True))
            export_rows(log.rows(), tmp_path / f"{kind}.{fmt}", fmt)
        con = sqlite3.connect(tmp_path / f"{kind}.sqlite")
        assert con.execute("SELECT decision, typeof(decision) FROM inspections ORDER BY id").fetchall() == [
            ("pass", "text"), ("reject", "text"), ("empty", "text"), ("not_inspected", "text")]
        con.close()
        files.append((tmp_path / f"{kind}.{fmt}").read_bytes())
    assert files[0] == files[1]



REASONS = {  # a reject reason as the station words it -> the cause the report counts it under
    "score 0.9100 > threshold 0.8800": "score over threshold",
    "not judged in time: 130.2 ms > cycle time 100.0 ms (before the model could start)": "not judged in time",
    "not judged: no frame for part T3: the camera missed its trigger pulse: the next frame (4) was exposed 140 ms "
    "after its TRIG": "camera missed trigger pulse",
    "not judged: no frame for part T3: its frame was lost in transport (a gap in frame ids)": "frame lost",
    "frame 12 lost before reaching the host": "frame lost",
    "not judged: no frame for part T3: no frame within 1000 ms": "no frame",
    "not judged: camera error for part T3: camera lost": "no frame",
    "not judged: no usable frame for part T3: ValueError: bad": "no frame",
    "not judged: model busy: still on part T2 after 230 ms": "model busy or failed",
    "not judged: frame 3: model default failed: RuntimeError: x": "model busy or failed",
    "not judged: model score is nan": "model busy or failed",
    "not judged: 2.00 % of input pixels invalid (limit 1.00 %)": "invalid pixels",
    "not recorded: disk full; judged pass": "log not writable",
    "not answered in time: the PASS was not delivered before the part's deadline": "PLC link",
    "not judged: station stopping": "station stopping",
    "dropped: processing queue full (drop_oldest)": "queue full",
    "no part in view: DoLP contrast 0.012 < 0.100": "no part in view",
    "something new": "other",
    # a station with a second camera (station.decision.join): its rejects alone are named; a part both reject is the
    # first camera's
    "second camera: score 0.9990 > threshold 0.9895": "second camera: score over threshold",
    "second camera: not judged: frame 9: model side failed: RuntimeError: x": "second camera: model busy or failed",
    "score 0.9900 > threshold 0.9785; second camera: not judged: model score is nan": "score over threshold",
    "not judged: the second camera sees no part (no part in view: row contrast 0.012 < 0.100), the first camera sees "
    "one": "no part in view",
}


def test_report_counts_rejects_by_cause(tmp_path):
    from station.log_report import format_summary, summarize

    with InspectionLog(tmp_path / "log.sqlite") as log:
        log.append([rec(i, "reject", reason=reason) for i, reason in enumerate(REASONS)]
                   + [rec(100, "pass"), rec(101, "empty", reason="dolp contrast 0.01 < 0.10")])
        s = summarize(log.rows())
    expected = Counter(REASONS.values())
    assert s.reject_causes == dict(expected)
    text = format_summary(s)
    assert "rejects by cause:" in text and all(f"{cause} {n}" in text for cause, n in expected.items())


def test_each_reject_cause_matches_a_wording_the_station_uses():
    """A reworded reason must not fall silently into "other": each cause's text is in the station's source."""
    from station.log_report import REJECT_CAUSES

    source = "\n".join(p.read_text() for d in ("station", "drivers", "model") for p in (ROOT / d).rglob("*.py")
                       if p.name != "log_report.py")
    for cause, needles in REJECT_CAUSES:
        assert any(n in source for n in needles), f"no reason in the code reads like {cause!r}: {needles}"


def test_a_command_that_cannot_write_its_output_says_so_in_one_line(tmp_path):
    """station report --out onto a file, and an export into a "folder" that is a file, printed tracebacks."""
    db = tmp_path / "log.sqlite"
    with InspectionLog(db) as log:
        log.append([rec(0)])
    taken = tmp_path / "taken"
    taken.write_text("a file, not a folder")
    for argv, first_line in ((["report", "--out", str(taken)], "station report: error: --out"),
                             (["export-log", "--out", str(taken / "x.csv")],
                              f"station export-log: error: {taken / 'x.csv.partial'}: Not a directory")):
        r = subprocess.run([sys.executable, "-m", "station.cli", *argv, "--db", str(db)], capture_output=True,
                           text=True)
        assert r.returncode == 2 and "Traceback" not in r.stderr
        assert len(r.stderr.strip().splitlines()) == 1 and r.stderr.startswith(first_line)


def test_the_manuals_state_the_schema_version_the_log_writes() -> None:
    """README and docs/inspection-log.md name the log's schema version: the one ``InspectionLog`` writes (the README
    said 5 through three version bumps)."""
    import re
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    readme = re.search(r"SQLite's `user_version` \((\d+)\)", (root / "README.md").read_text())
    manual = re.search(r"SQLite's `user_version` \(now (\d+):", (root / "docs" / "inspection-log.md").read_text())
    assert readme and manual and int(readme[1]) == int(manual[1]) == SCHEMA_VERSION
