"""``station export-log``: stream the inspection log (or a time/decision slice of it) to csv, jsonl or parquet."""

from __future__ import annotations

import argparse
import math
from datetime import datetime

from station.errors import UserError
from station.inspection_log import DECISIONS, EXPORT_FORMATS, InspectionLog, export_rows


def parse_time(text: str) -> float:
    """Unix seconds from a number or an ISO 8601 time (without a zone: local time)."""
    try:
        value = float(text)
    except ValueError:
        pass
    else:
        if not math.isfinite(value):  # nan compares false with every time: the slice would be silently empty
            raise argparse.ArgumentTypeError(f"{text!r}: not a time")
        return value
    try:
        return datetime.fromisoformat(text).timestamp()
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{text!r}: expected unix seconds or ISO 8601 (e.g. 2026-11-23T08:00)") from None


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("export-log", help="export the inspection log to csv, jsonl or parquet",
                       description="Columns: id, then InspectionRecord's fields (see README, 'Inspection log').")
    p.add_argument("--db", default="runs/inspection.sqlite", help="inspection log (SQLite)")
    p.add_argument("--format", choices=EXPORT_FORMATS, help="default: from the --out suffix")
    p.add_argument("--since", type=parse_time, help="first time (unix s or ISO 8601), inclusive")
    p.add_argument("--until", type=parse_time, help="last time (unix s or ISO 8601), exclusive")
    p.add_argument("--decision", choices=DECISIONS, help="only rows with this decision")
    p.add_argument("--out", required=True, help="output file")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    fmt = args.format or args.out.rsplit(".", 1)[-1]
    if fmt not in EXPORT_FORMATS:
        raise UserError(f"--out {args.out}: cannot tell the format from the suffix; give --format "
                        f"({', '.join(EXPORT_FORMATS)})")
    with InspectionLog(args.db, readonly=True) as log:
        n = export_rows(log.rows(args.since, args.until, args.decision), args.out, fmt)
    print(f"exported {n} rows from {args.db} to {args.out} ({fmt})")
    return 0
