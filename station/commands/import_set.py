"""``station import``: captured (or foreign) raw mosaics in the MVTec AD layout -> a dataset the station's commands
read (``station train/eval/threshold/adapt --data``). The work is ``station.mvtec.import_mvtec``."""

from __future__ import annotations

import argparse

from station.commands.arguments import seed


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("import", help="import raw mosaics in the MVTec AD layout (train/good, test/<type>, "
                                      "ground_truth) as a dataset")
    p.add_argument("--from", dest="src", required=True, metavar="DIR",
                   help="MVTec-layout folder: train/good/, test/good/, test/<defect type>/, optional val/, "
                        "ground_truth/<type>/<name>_mask.png, object_masks/")
    p.add_argument("--out", required=True, metavar="DATASET", help="new dataset folder")
    p.add_argument("--bit-depth", type=int, default=None, choices=(8, 10, 12, 14, 16),
                   help="significant bits of the codes (default: DIR/polar_ano.json's, else 8 for 8-bit files; "
                        "16-bit files need it, e.g. 12 for a Mono12 camera)")
    p.add_argument("--layout", default=None,
                   help="on-chip polarizer layout (default: DIR/polar_ano.json's, else imx250mzr)")
    p.add_argument("--val-fraction", type=float, default=0.1,
                   help="without a val/ folder: share of train/good held out as the validation split (default 0.1)")
    p.add_argument("--seed", type=seed, default=0, help="which train/good images go to val (default 0)")
    p.add_argument("--allow-dark", action="store_true",
                   help="accept a 16-bit set whose codes all fit fewer bits (default: refused as a wrong bit depth)")
    p.add_argument("--defect-pixels", default=None, metavar="PNG",
                   help="the camera's defect pixel map (`station defect-pixels`), copied into the set: every "
                        "command that reads it fills those pixels, as the station does with [camera] defect_pixels "
                        "(default: the map DIR/polar_ano.json names, which station capture records)")
    p.add_argument("--black-level", type=int, default=None, metavar="CODES",
                   help="the camera's black level in the files' codes (`station defect-pixels` measures it), named "
                        "in the set: every command that reads it removes it, as the station does with [camera] "
                        "black_level (default: DIR/polar_ano.json's, which station capture records, else 0)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from station.errors import UserError
    from station.mvtec import import_mvtec

    if not 0.0 <= args.val_fraction < 1.0:
        raise UserError(f"--val-fraction {args.val_fraction}: a fraction in [0, 1)")
    report = import_mvtec(args.src, args.out, args.bit_depth, args.layout, args.val_fraction, args.seed,
                          args.allow_dark, defect_pixels=args.defect_pixels,
                          black_level=args.black_level)
    print(report.describe())
    return 0
