"""``station shape``: add the shape check (``model.draem.shape_check``, rule 70) to a model with a variation model:
how far the part's bottom edge bends, a finding beside the window's for a part bowed along its length.

Its edge comes from the variation model's reference and region; the sag's median and spread from ``--data``'s good
train parts (the variation model's fit set), its threshold from the good parts of ``--val-data``'s val split (the
largest of theirs). The model is copied otherwise unchanged, its threshold too; the sidecar records the check
(``train.shape``).
"""

from __future__ import annotations

import argparse


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("shape", help="add the shape check (how far the part's bottom edge bends: a bowed part) to a "
                                     "model with a variation model")
    p.add_argument("--model", required=True, help="checkpoint with a variation model, path without suffix")
    p.add_argument("--data", required=True, help="the variation model's training set (its good train parts)")
    p.add_argument("--val-data", required=True, metavar="DATA",
                   help="set whose val split's good parts set the check's threshold (the variation model's "
                        "calibration set)")
    p.add_argument("--out", required=True, help="checkpoint to write, path without suffix")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from station.evaluation import fit_shape

    print(fit_shape(args.model, args.data, args.val_data, args.out))
    return 0
