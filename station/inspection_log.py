"""The inspection log: one SQLite row per part, durable on commit, with streaming export.

SQLite in WAL mode with ``synchronous=FULL``: a row whose ``append`` returned survives a crash or power loss; the
WAL is checkpointed and truncated often (``WAL_CHECKPOINT_PAGES``) so that it stays small. A file that is not an
inspection log (another program's tables, a newer schema) is refused before anything in it is changed.
The schema version is ``PRAGMA user_version``; columns carry their unit in the name. Version 2 added
``ground_truth_present``, version 3 the frame statistics (``median_level``, ``high_level``, ``clipped_fraction``,
``dolp_level``: ``model.priors.frame_stats``) and ``drift`` (the drift warning in force when the part was judged,
``station.drift``), version 4 the model's frame checks (``highlight_fraction``, ``noise_level``: ``FRAME_CHECKS``),
version 5 the second camera's (``second_score``, ``second_threshold``, ``second_model_id``, ``second_frame_id``:
``station.second_camera``), version 6 the shape check's ``edge_bend``, version 7 the outline check's ``edge_step``,
version 8 ``unseen_fraction``, the share of the part outside the model's view, version 9 ``turn_deg``, how far the
part lay turned from the model's good parts, version 10 ``look_level``, the look network's finding over its blend
threshold (``FRAME_CHECKS``).
Opening an older log for writing adds the missing columns (NULL in the old rows); opened
read-only, they read as NULL. Decisions (``station.decision.Verdict``, stored as its values):

pass           judged good (score <= threshold)
reject         judged bad (score > threshold), or could not be judged (fail closed; ``reason`` says why)
empty          no part in view; not judged, not rejected
not_inspected  frame dropped before judgement (queue full, grab failure); ``reason`` says why
"""

from __future__ import annotations

import csv
import json
import sqlite3
import time
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any

from station.decision import Verdict
from station.errors import UserError

SCHEMA_VERSION = 10
WAL_CHECKPOINT_PAGES = 64
"""Checkpoint the write-ahead log every 64 pages (256 KiB) instead of SQLite's 1000 ..."""
WAL_SIZE_LIMIT_BYTES = 256 * 1024
"""... and truncate it back to this size afterwards: a small disk holds rows, not a stale WAL."""
LOGGED_STATISTICS = ("median_level", "high_level", "clipped_fraction", "dolp_level")
"""The frame statistics (``model.priors.frame_stats``) a row keeps; the others reach the log through ``drift``."""
ADDED_IN_VERSION = {2: ("ground_truth_present",),
                    3: (*LOGGED_STATISTICS, "drift"),
                    4: ("highlight_fraction", "noise_level"),
                    5: ("second_score", "second_threshold", "second_model_id", "second_frame_id"),
                    6: ("edge_bend",),
                    7: ("edge_step",),
                    8: ("unseen_fraction",),
                    9: ("turn_deg",),
                    10: ("look_level",)}
"""Columns each schema version added (older logs gain them, NULL in old rows, when a station writes to them)."""
READABLE_VERSIONS = (1, 2, 3, 4, 5, 6, 7, 8, 9, 10)
DECISIONS: tuple[str, ...] = tuple(v.value for v in Verdict)
"""The values of ``Verdict`` as the log stores them: "pass", "reject", "empty", "not_inspected"."""
STAGES = ("grab", "demosaic", "priors", "model", "decision", "io", "total")
EXPORT_FORMATS = ("csv", "jsonl", "parquet")


class LogError(UserError):
    """The inspection log cannot be opened, written or read (path and SQLite's reason in the message)."""


@dataclass(frozen=True)
class InspectionRecord:
    """One part. Times: ``time_unix_s`` when judged (host clock); latencies in milliseconds per stage, the part's
    ``total_ms`` from its TRIG reaching the host (trigger-free: the grab's start) to the decision. The row is
    written before the PLC hears the decision (write-ahead); ``io_delivered`` is False until the PLC acknowledges
    it, then True with ``io_ms`` the time from decision to acknowledgement (False for good if it never does);
    both None when there is no PLC to tell."""

    decision: Verdict
    """Given as a ``Verdict`` or its value (a value is turned into its ``Verdict``)."""
    time_unix_s: float
    part_id: str | None = None
    camera_frame_id: int | None = None
    camera_timestamp_ns: int | None = None
    score: float | None = None
    threshold: float | None = None
    model_id: str | None = None
    reason: str | None = None
    grab_ms: float | None = None
    demosaic_ms: float | None = None
    priors_ms: float | None = None
    model_ms: float | None = None
    decision_ms: float | None = None
    io_ms: float | None = None
    total_ms: float | None = None
    io_delivered: bool | None = None
    ground_truth_label: int | None = None
    """1 defective, 0 good, for a simulated part in view; None without ground truth or with no part in view."""
    ground_truth_present: bool | None = None
    """Whether the simulated frame showed a part (scores the presence check); None without ground truth."""
    image_path: str | None = None
    median_level: float | None = None
    """Frame statistics over the station's region (``model.priors.frame_stats``): median and 95th percentile of the
    intensity and median DoLP (full-scale units 0..1), share of clipped mosaic pixels; None when not computed."""
    high_level: float | None = None
    clipped_fraction: float | None = None
    dolp_level: float | None = None
    drift: str | None = None
    """The drift warnings in force when the part was judged (``station.drift.DriftMonitor``, ``ViewMonitor``; "; "
    between two); None in range."""
    highlight_fraction: float | None = None
    """Share of the part (0..1) the model found lit to full scale, and did not judge there; above 0.5 it judged the
    whole part. None when the model has no variation member or did not run."""
    noise_level: float | None = None
    """The frame's noise against the good parts the model was fitted on (about 1 there): the model reads a frame up
    to ``model.draem.variation.NOISE_CAP`` times noisier as noise and judges a noisier one as it is (it rejects).
    Parts well above 1 come from a line unlike the model's: ``station adapt``. None as for highlight_fraction."""
    second_score: float | None = None
    """A station with a second camera (``[second_camera]``): its model's score, threshold, model id and frame id for
    the part (``score``, ``threshold``, ``model_id`` and ``camera_frame_id`` are the first camera's); None with one
    camera, or where the second camera gave no frame or score."""
    second_threshold: float | None = None
    second_model_id: str | None = None
    second_frame_id: int | None = None
    edge_bend: float | None = None
    """How far the part's bottom edge bends, as the shape check's robust z over its threshold (signed; beyond +-1
    it bends further than any good validation part's, and the part's reason says so: ``model.draem.frame_checks``).
    None when the model has no shape check, the edge was not seen, or the model did not run."""
    edge_step: float | None = None
    """How far the part's outline steps along its long edges (flash, a broken edge), as the outline check's largest
    run z over its threshold (beyond 1 further than any good calibration part's, and the reason says so:
    ``model.draem.frame_checks``). None when the model has no outline check, the edges were not seen, or the model
    did not run."""
    unseen_fraction: float | None = None
    """The share of the part region the model's registration took from outside the frame (0-1; above
    ``model.draem.frame_checks.UNSEEN_LIMIT``, 0, a reject's reason says the part lay partly outside the model's view:
    a camera turned from square, a part off its place). None without a variation model or when the model did not
    run."""
    turn_deg: float | None = None
    """How far the part lay turned from the good parts the model was calibrated on (degrees, positive clockwise as the
    frame is shown; ``model.draem.variation``: turn). Beyond ``model.draem.frame_checks.TURN_LIMIT_DEG`` a reject's
    reason says so; a median beyond ``station.drift.TURN_WARN_DEG`` over the recent parts is the turn warning. None
    without a variation model, for a file without ``turn_centre``, or when the model did not run."""
    look_level: float | None = None
    """The look network's finding over its blend threshold (``model.draem.frame_checks``; 1 where the network alone
    would reject). A median above ``station.drift.LOOK_WARN_LEVEL`` over the recent parts is the look warning. None for
    a file without the blend, or when the model did not run."""

    def __post_init__(self) -> None:
        if self.decision not in DECISIONS:
            raise ValueError(f"decision must be one of {DECISIONS}, got {self.decision!r}")
        object.__setattr__(self, "decision", Verdict(self.decision))


COLUMNS = tuple(f.name for f in fields(InspectionRecord))
_SQL_TYPES = {"decision": "TEXT NOT NULL", "time_unix_s": "REAL NOT NULL", "part_id": "TEXT", "model_id": "TEXT",
              "reason": "TEXT", "image_path": "TEXT", "camera_frame_id": "INTEGER", "camera_timestamp_ns": "INTEGER",
              "io_delivered": "INTEGER", "ground_truth_label": "INTEGER",
              "ground_truth_present": "INTEGER", "drift": "TEXT", "second_model_id": "TEXT",
              "second_frame_id": "INTEGER"}
_BOOL_COLUMNS = ("io_delivered", "ground_truth_present")


def _create_sql() -> str:
    cols = ",\n  ".join(f"{c} {_SQL_TYPES.get(c, 'REAL')}" for c in COLUMNS)
    return (f"CREATE TABLE IF NOT EXISTS inspections (\n  id INTEGER PRIMARY KEY AUTOINCREMENT,\n  {cols}\n);\n"
            "CREATE INDEX IF NOT EXISTS inspections_time ON inspections(time_unix_s);")


def _db_error(path: Path, action: str, exc: sqlite3.Error) -> LogError:
    hint = ""
    text = str(exc).lower()
    if "full" in text:
        hint = " (disk full)"
    elif "readonly" in text or "read-only" in text or "unable to open" in text:
        hint = " (read-only location or missing folder?)"
    return LogError(f"inspection log {path}: cannot {action}: {exc}{hint}")


class InspectionLog:
    """Append-only inspection log in one SQLite file. Not thread-safe: one thread at a time uses it (it may be
    opened in one thread and written by another, as the station's processing thread does)."""

    def __init__(self, path: str | Path, *, readonly: bool = False) -> None:
        self.path = Path(path)
        if self.path.is_dir():
            raise LogError(f"inspection log {self.path}: a folder, not a file (give the .sqlite file)")
        try:
            if readonly:
                if not self.path.exists():
                    raise LogError(f"inspection log {self.path}: no such file")
                # opened where a reader is built, read from its thread (station view's follower): handed over
                self._db = sqlite3.connect(f"file:{self.path}?mode=ro", uri=True, check_same_thread=False)
            else:
                self.path.parent.mkdir(parents=True, exist_ok=True)
                self._db = sqlite3.connect(self.path, check_same_thread=False)  # handed over, never shared
                self._refuse_foreign()  # before anything below changes the file
                self._db.execute("PRAGMA journal_mode=WAL")
                self._db.execute("PRAGMA synchronous=FULL")
                self._db.execute(f"PRAGMA wal_autocheckpoint={WAL_CHECKPOINT_PAGES}")
                self._db.execute(f"PRAGMA journal_size_limit={WAL_SIZE_LIMIT_BYTES}")
                self._db.executescript(_create_sql())
                version = self._db.execute("PRAGMA user_version").fetchone()[0]
                if version == 0:
                    self._db.execute(f"PRAGMA user_version={SCHEMA_VERSION}")
                elif version < SCHEMA_VERSION:
                    have = {r[1] for r in self._db.execute("PRAGMA table_info(inspections)")}
                    with self._db:  # one transaction: the columns and the version change together
                        for v in range(version + 1, SCHEMA_VERSION + 1):
                            for c in (c for c in ADDED_IN_VERSION[v] if c not in have):
                                self._db.execute(f"ALTER TABLE inspections ADD COLUMN {c} {_SQL_TYPES.get(c, 'REAL')}")
                        self._db.execute(f"PRAGMA user_version={SCHEMA_VERSION}")
                self._db.commit()
            version = self._db.execute("PRAGMA user_version").fetchone()[0]
            have = {r[1] for r in self._db.execute("PRAGMA table_info(inspections)")}
        except OSError as exc:
            raise LogError(f"inspection log {self.path}: cannot open: {exc}") from None
        except sqlite3.Error as exc:
            raise _db_error(self.path, "open", exc) from None
        if version not in READABLE_VERSIONS:
            raise LogError(f"inspection log {self.path}: schema version {version}, this station reads "
                           f"{READABLE_VERSIONS[0]} to {SCHEMA_VERSION}; export it with the station version that "
                           f"wrote it")
        self._select = ", ".join(c if c in have else f"NULL AS {c}" for c in COLUMNS)

    def _refuse_foreign(self) -> None:
        """LogError when the file is another program's database or a newer log: checked on a fresh connection
        before this class changes anything (journal mode, tables, version)."""
        version = self._db.execute("PRAGMA user_version").fetchone()[0]
        tables = {n for (n,) in self._db.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
        tables.discard("sqlite_sequence")
        if version not in (0, *READABLE_VERSIONS):
            raise LogError(f"inspection log {self.path}: schema version {version}, this station reads "
                           f"{READABLE_VERSIONS[0]} to {SCHEMA_VERSION}; export it with the station version that "
                           f"wrote it (file left as it was)")
        foreign = sorted(tables - {"inspections"})
        if foreign or (version and "inspections" not in tables):
            raise LogError(f"inspection log {self.path}: another program's SQLite database (tables "
                           f"{', '.join(foreign) or 'none of ours'}); choose another [log] path (file left as it was)")
        if "inspections" in tables:
            have = {r[1] for r in self._db.execute("PRAGMA table_info(inspections)")}
            unknown = sorted(have - {"id", *COLUMNS})
            if unknown:
                raise LogError(f"inspection log {self.path}: table inspections has columns this station does not "
                               f"know ({', '.join(unknown[:5])}); choose another [log] path (file left as it was)")

    def append(self, records: InspectionRecord | Sequence[InspectionRecord]) -> list[int]:
        """Write and commit records; durable when this returns; their row ids. A full disk raises LogError
        (nothing half-written: the transaction is rolled back)."""
        batch = [records] if isinstance(records, InspectionRecord) else list(records)
        rows = [tuple(getattr(r, c) for c in COLUMNS) for r in batch]
        sql = f"INSERT INTO inspections ({', '.join(COLUMNS)}) VALUES ({', '.join('?' * len(COLUMNS))})"
        try:
            with self._db:
                return [int(self._db.execute(sql, row).lastrowid) for row in rows]
        except sqlite3.Error as exc:
            raise _db_error(self.path, f"write {len(rows)} record(s)", exc) from None

    def amend_decision(self, row_id: int, decision: Verdict | str, reason: str) -> None:
        """Change one row's decision and reason (a pass found late after its row was written becomes a reject
        before the PLC hears of it); LogError when it cannot be written."""
        if decision not in DECISIONS:
            raise ValueError(f"decision must be one of {DECISIONS}, got {decision!r}")
        try:
            with self._db:
                self._db.execute("UPDATE inspections SET decision = ?, reason = ? WHERE id = ?",
                                 (decision, reason, row_id))
        except sqlite3.Error as exc:
            raise _db_error(self.path, f"amend row {row_id}", exc) from None

    def set_delivered(self, outcomes: Mapping[int, tuple[bool, float | None]]) -> None:
        """Set ``io_delivered`` and ``io_ms`` of rows (by id): whether the PLC acknowledged the part's decision,
        and how long after the decision. One transaction; LogError (nothing changed) when it cannot be written."""
        if not outcomes:
            return
        try:
            with self._db:
                self._db.executemany("UPDATE inspections SET io_delivered = ?, io_ms = ? WHERE id = ?",
                                     [(int(ok), ms, k) for k, (ok, ms) in outcomes.items()])
        except sqlite3.Error as exc:
            raise _db_error(self.path, f"record the PLC's answer for {len(outcomes)} row(s)", exc) from None

    def count(self, decision: str | None = None) -> int:
        sql, args = "SELECT COUNT(*) FROM inspections", ()
        if decision is not None:
            sql, args = sql + " WHERE decision = ?", (decision,)
        return int(self._db.execute(sql, args).fetchone()[0])

    def last_id(self) -> int:
        """The newest row's ``id`` (0 for an empty log)."""
        return int(self._db.execute("SELECT COALESCE(MAX(id), 0) FROM inspections").fetchone()[0])

    def rows(self, since_unix_s: float | None = None, until_unix_s: float | None = None,
             decision: str | None = None, batch_size: int = 1000, after_id: int | None = None
             ) -> Iterator[dict[str, Any]]:
        """Records as dicts (``id`` first, then ``COLUMNS``) in time order, streamed in batches; ``after_id``:
        only rows written after that row (for following a live log)."""
        where, args = [], []
        if after_id is not None:
            where.append("id > ?")
            args.append(after_id)
        if since_unix_s is not None:
            where.append("time_unix_s >= ?")
            args.append(since_unix_s)
        if until_unix_s is not None:
            where.append("time_unix_s < ?")
            args.append(until_unix_s)
        if decision is not None:
            where.append("decision = ?")
            args.append(decision)
        sql = f"SELECT id, {self._select} FROM inspections"
        if where:
            sql += " WHERE " + " AND ".join(where)
        cur = self._db.execute(sql + " ORDER BY time_unix_s, id", args)
        names = [d[0] for d in cur.description]
        while batch := cur.fetchmany(batch_size):
            for values in batch:
                row = dict(zip(names, values, strict=True))
                for c in _BOOL_COLUMNS:
                    if row[c] is not None:
                        row[c] = bool(row[c])
                yield row

    def apply_retention(self, retention_days: float, now_unix_s: float | None = None) -> list[str]:
        """Delete rows older than ``retention_days`` (0 = keep all); return the image paths they referenced."""
        if retention_days <= 0:
            return []
        cutoff = (now_unix_s if now_unix_s is not None else time.time()) - retention_days * 86400.0
        try:
            with self._db:
                images = [p for (p,) in self._db.execute(
                    "SELECT image_path FROM inspections WHERE time_unix_s < ? AND image_path IS NOT NULL", (cutoff,))]
                self._db.execute("DELETE FROM inspections WHERE time_unix_s < ?", (cutoff,))
        except sqlite3.Error as exc:
            raise _db_error(self.path, "apply retention", exc) from None
        return images

    def close(self) -> None:
        self._db.close()

    def __enter__(self) -> InspectionLog:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def export_rows(rows: Iterator[dict[str, Any]], out: str | Path, fmt: str, batch_size: int = 1000) -> int:
    """Stream ``rows`` to ``out`` as csv, jsonl or parquet; return the number written. Columns: ``id`` +
    ``COLUMNS`` (see ``InspectionRecord``). The file is written under a temporary name and renamed when complete."""
    if fmt not in EXPORT_FORMATS:
        raise LogError(f"export format {fmt!r} is not one of {', '.join(EXPORT_FORMATS)}")
    out = Path(out)
    if fmt == "parquet":
        try:
            import pyarrow  # noqa: F401
        except ImportError:
            raise LogError(f"export to {out}: parquet needs pyarrow, the extra [parquet] "
                           f"(pip install 'polar-ano-station[parquet]'); csv and jsonl need nothing") from None
    tmp = out.with_name(out.name + ".partial")
    names = ["id", *COLUMNS]
    n = 0
    try:
        if fmt == "parquet":
            n = _export_parquet(rows, tmp, names, batch_size)
        else:
            with tmp.open("w", newline="", encoding="utf-8") as f:
                writer = csv.DictWriter(f, fieldnames=names) if fmt == "csv" else None
                if writer:
                    writer.writeheader()
                for row in rows:
                    if writer:
                        writer.writerow(row)
                    else:
                        f.write(json.dumps(row) + "\n")
                    n += 1
        tmp.replace(out)
    except OSError as exc:
        tmp.unlink(missing_ok=True)
        raise LogError(f"export to {out}: {exc}") from None
    return n


def _export_parquet(rows: Iterator[dict[str, Any]], path: Path, names: list[str], batch_size: int) -> int:
    import pyarrow as pa
    import pyarrow.parquet as pq

    def arrow_type(column: str) -> pa.DataType:  # from the SQLite column's type (``_SQL_TYPES``): one place
        if column in _BOOL_COLUMNS:
            return pa.bool_()
        sql = "INTEGER" if column == "id" else _SQL_TYPES.get(column, "REAL")
        return {"TEXT": pa.string(), "INTEGER": pa.int64()}.get(sql.split()[0], pa.float64())

    schema = pa.schema([(c, arrow_type(c)) for c in names])
    n = 0
    with pq.ParquetWriter(path, schema) as writer:
        batch: list[dict[str, Any]] = []
        for row in rows:
            batch.append(row)
            if len(batch) >= batch_size:
                writer.write_table(pa.Table.from_pylist(batch, schema=schema))
                n, batch = n + len(batch), []
        if batch or n == 0:
            writer.write_table(pa.Table.from_pylist(batch, schema=schema))
            n += len(batch)
    return n
