"""``station shape``: add the shape checks to a model with a variation model: the shape check
(``model.draem.shape_check``, rule 70), how far the part's bottom edge bends, for a part bowed along its length; and
the outline check (``model.draem.outline_check``), a short step along the part's two long edges, for flash or a
broken edge. Each is a finding beside the window's.

Their edges come from the variation model's reference and region; their medians and spreads from ``--data``'s good
train parts (the variation model's fit set), their thresholds from the good parts of ``--val-data``'s val split (the
largest of theirs). A part too small for the outline check's runs, or too few parts showing its edges, leave it off
(the output line says why). The model is copied otherwise unchanged, its threshold too; the sidecar records the
checks (``train.shape``).
"""

from __future__ import annotations

import argparse


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("shape", help="add the shape checks (how far the part's bottom edge bends: a bowed part; a "
                                     "step along its edges: flash) to a model with a variation model")
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
