"""``station report``: counts, reject rate, latency percentiles and score histogram of a log, with a plot."""

from __future__ import annotations

import argparse
import json
from dataclasses import asdict
from pathlib import Path

from station.commands.export_log import parse_time
from station.errors import UserError
from station.inspection_log import InspectionLog
from station.log_report import format_summary, plot_summary, summarize


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("report", help="summarize an inspection log (table, JSON and a PNG plot)")
    p.add_argument("--db", default="runs/inspection.sqlite", help="inspection log (SQLite)")
    p.add_argument("--since", type=parse_time, help="first time (unix s or ISO 8601)")
    p.add_argument("--until", type=parse_time, help="last time (unix s or ISO 8601), exclusive")
    p.add_argument("--out", default="runs/report", help="folder for report.json and report.png")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    with InspectionLog(args.db, readonly=True) as log:
        summary = summarize(log.rows(args.since, args.until))
        thresholds = {r["threshold"] for r in log.rows(args.since, args.until) if r["threshold"] is not None}
    out = Path(args.out)
    threshold = thresholds.pop() if len(thresholds) == 1 else None
    try:
        out.mkdir(parents=True, exist_ok=True)
        (out / "report.json").write_text(json.dumps(asdict(summary), indent=2))
        png = plot_summary(summary, threshold, out / "report.png")
    except OSError as exc:
        raise UserError(f"--out {out}: cannot write the report there: {exc.strerror or exc}") from None
    print(format_summary(summary))
    print(f"wrote {out / 'report.json'} and {png}")
    return 0
