"""``station adapt``: adapt a trained model to a line from good parts captured there (``station capture`` ->
``station import``): input normalisation refitted, optional brief fine-tune, threshold set so that the stated
share of held-out good parts is rejected; the sidecar records what it was adapted on. Policy:
``model.draem.adapt``; glue: ``station.adaptation``."""

from __future__ import annotations

import argparse

from model.draem.config import GOOD_REJECTED_RATE
from station.commands.arguments import add_presence_rule, positive_int, seed


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("adapt", help="adapt a model to a line from good parts (normalisation, threshold)")
    p.add_argument("--model", required=True, help="checkpoint path without suffix (e.g. model/weights/default)")
    p.add_argument("--good", required=True, metavar="DATASET", help="set with good parts of the line (station import)")
    p.add_argument("--out", required=True, help="adapted checkpoint path without suffix (e.g. runs/line/adapted)")
    p.add_argument("--false-reject", type=float, default=GOOD_REJECTED_RATE,
                   help=f"share of good parts the threshold may reject (default {GOOD_REJECTED_RATE})")
    p.add_argument("--split", default="train", choices=("train", "val", "test"),
                   help="split whose good parts are used (default train: an imported train/good)")
    p.add_argument("--limit", type=positive_int, default=None, help="use at most N parts of the split (default all)")
    p.add_argument("--fine-tune-steps", type=int, default=0,
                   help="also fine-tune this many steps with synthetic anomalies (default 0: off)")
    p.add_argument("--seed", type=seed, default=0, help="fold assignment and fine-tune randomness (default 0)")
    p.add_argument("--keep-networks", action="store_true",
                   help="keep the networks in the decision even when their good-part scores on this line are out of "
                        "their domain (default: the adapted model then decides on the variation model alone)")
    p.add_argument("--floor-checks", action=argparse.BooleanOptionalAction, default=None,
                   help="floor the refitted shape and outline checks' thresholds at the model's own, set on its "
                        "calibration parts (default: on; --no-floor-checks lets few good parts set them lower, "
                        "which rejected 9 of 206 good parts instead of 2 after adapting on 90: "
                        "docs/results/2026-12-05-adapt-floor.md)")
    add_presence_rule(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from station.adaptation import adapt_model

    print(adapt_model(args.model, args.good, args.out, args.split, args.limit, args.false_reject,
                      args.fine_tune_steps, args.seed, args.keep_networks, args.presence_rule,
                      args.floor_checks).describe())
    return 0
