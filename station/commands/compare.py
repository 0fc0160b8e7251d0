"""``station compare``: several ``station eval`` reports side by side per defect type (``station.eval_compare``):
the held-out report of a model trained on rendered defects, the same recipe without one type, and the
synthetic-only model; or, with ``--paired``, models on the same parts with the paired standard error of their
difference; or, with ``--split``, a two-camera station on the same parts (``station split``'s thresholds)."""

from __future__ import annotations

import argparse

from station.commands.arguments import positive_int


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("compare", help="station eval reports side by side per defect type (trained on, held out, "
                                       "synthetic only)")
    p.add_argument("reports", nargs="+", metavar="EVAL_DIR", help="station eval --out folders")
    p.add_argument("--out", required=True, help="folder for compare.md, compare.json and compare.png")
    p.add_argument("--no-plots", action="store_true")
    p.add_argument("--paired", action="store_true",
                   help="compare each report with the first on the same parts (their scores.csv): image AUROC "
                        "gain overall and per type with its paired bootstrap standard error")
    p.add_argument("--resamples", type=positive_int, default=1000, help="bootstrap resamples for --paired (1000)")
    p.add_argument("--split", default=None, metavar="SPLIT_JSON",
                   help="two reports, the two cameras' on twin held-out sets: the two-camera station at the "
                        "thresholds of this station split report, beside each camera alone")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from station.errors import UserError
    from station.eval_compare import compare, paired, two_cameras

    if args.split:
        if len(args.reports) != 2 or args.paired:
            raise UserError("--split takes two reports (the first camera's, then the second's) and no --paired")
        print(two_cameras(*args.reports, args.split, args.out)[1])
    elif args.paired:
        print(paired(args.reports, args.out, args.resamples)[1])
    else:
        print(compare(args.reports, args.out, not args.no_plots)[1])
    return 0
