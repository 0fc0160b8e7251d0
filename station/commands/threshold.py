"""``station threshold``: set a checkpoint's decision threshold on a split of any set with good parts.

``station train`` sets the threshold of ``best`` (the keep-best checkpoint). This sets it for any checkpoint, e.g.
``last`` (the final step, which the published DRAEM keeps), with the same rule (``model.draem.metrics
.choose_threshold``: the lowest threshold that flags at most ``--max-good-flagged`` of the split's good parts,
the line's budget) and writes it into the checkpoint's sidecar. On another set
than the training set (frames captured at the line, ``station import``) the sidecar records which set and split
set the threshold (``train.threshold_set``); several sets pool their parts (more good parts: a steadier threshold
and a narrower promise, ``model.draem.rate_bounds``). Frames the station would not judge (no part in view for the
camera's presence rule, ``--presence-rule``; too many invalid pixels) are left out and listed. To adapt the input
normalisation as well, use ``station adapt``. A model with a variation member also takes its good parts' median turn
as the centre each part's turn is read from (``turn_deg``: the station's turn warning, ``station.drift``).
"""

from __future__ import annotations

import argparse

from station.commands.arguments import add_max_good_flagged, add_presence_rule
from station.errors import UserError


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("threshold", help="set a checkpoint's threshold on a split of any set with good parts")
    p.add_argument("--model", required=True, help="checkpoint path without suffix (e.g. runs/train/x/last)")
    p.add_argument("--data", required=True, nargs="+", metavar="DIR",
                   help="set with good parts: the training set, or another (rendered or imported) set of the line; "
                        "several sets (other seeds, captures of other days) pool their parts")
    p.add_argument("--split", default="val", choices=("train", "val", "test"),
                   help="split to choose on (default val; train only on a set the model was not trained on)")
    add_presence_rule(p)
    add_max_good_flagged(p, "the split's good parts")
    p.add_argument("--confidence", type=float, default=None, metavar="C",
                   help="promise --max-good-flagged for new good parts with confidence C (e.g. 0.95) instead of "
                        "counting it on these: a stricter threshold, which needs enough good parts (299 for 1 %% at "
                        "0.95; docs/model.md)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from station.evaluation import set_threshold

    if args.confidence is not None and not 0.0 < args.confidence < 1.0:
        raise UserError(f"--confidence {args.confidence}: a fraction in (0, 1)")
    print(set_threshold(args.model, args.data, args.max_good_flagged, args.split, args.presence_rule,
                        args.confidence))
    return 0
