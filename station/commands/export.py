"""``station export``: write a dataset in another tool's layout (``--format mvtec``: the MVTec AD folders that
anomalib and most anomaly-detection tools read). The work is ``station.mvtec.export_mvtec``."""

from __future__ import annotations

import argparse


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("export", help="write a rendered (or imported) set in the MVTec AD layout")
    p.add_argument("--data", required=True, help="dataset folder (station render --out or station import --out)")
    p.add_argument("--out", required=True, help="new folder for the exported layout")
    p.add_argument("--format", default="mvtec", choices=("mvtec",), help="layout to write (default mvtec)")
    p.add_argument("--no-object-masks", action="store_true",
                   help="leave out object_masks/ (our extension; other tools ignore it)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from station.mvtec import export_mvtec

    print(export_mvtec(args.data, args.out, object_masks=not args.no_object_masks).describe())
    return 0
