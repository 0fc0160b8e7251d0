"""``station pick``: of several trainings of one recipe (draws differing only in their seed), keep the one that
rejects fewest good parts of a set, each at its own stored threshold (``model.draem.draw_choice``: a tie goes to the
one catching more defective parts, then to the first named). The set is a validation set, never a test set: the
shipped recipe picks among its look networks on the validation parts seen through a lens drawn per part
(``LOOK_DRAWS`` in scripts/make-model.sh; docs/results/2026-12-11-look-draw.md). The kept file is copied to ``--out``,
its sidecar recording every draw's counts (``train.draw_choice``).
"""

from __future__ import annotations

import argparse

from station.commands.arguments import add_presence_rule


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("pick", help="keep, of several trainings of one recipe, the one rejecting fewest good parts "
                                    "of a validation set")
    p.add_argument("--models", required=True, nargs="+", metavar="MODEL",
                   help="two or more checkpoints (paths without suffix), each with its threshold; ties go to the "
                        "first named")
    p.add_argument("--data", required=True, help="set whose split's good (and defective) parts are counted")
    p.add_argument("--split", default="val", choices=("train", "val", "test"), help="split to count on")
    p.add_argument("--out", required=True, help="checkpoint to write the kept file to, path without suffix")
    add_presence_rule(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from station.evaluation import pick_draw

    print(pick_draw(args.models, args.data, args.out, args.split, args.presence_rule))
    return 0
