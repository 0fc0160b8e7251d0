"""``station blend``: ask a model's look network about every part and blend its finding with the window's
(``model.draem.residual.blended``): a part scores its window threshold times the larger of ``--weight`` of the
window's finding plus the rest of the network's, each over its own 1 % threshold on ``--data``'s good val parts, and
the shape and outline checks' finding whole. The file's cascade (the network asked only about parts above the second
look's gate) is replaced; the threshold is then set on the same split with ``station threshold``'s rule. The sidecar
records the blend (``train.blend``). Measured on fresh sets: docs/results/2026-12-07-blend-rates.md.
"""

from __future__ import annotations

import argparse

from station.commands.arguments import add_max_good_flagged


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("blend", help="blend a model's look network with its window on every part (the shipped "
                                     "recipe) instead of asking it about suspicious parts only")
    p.add_argument("--model", required=True, help="checkpoint whose residual networks are its second look (station "
                                                  "residual --second-look), path without suffix")
    p.add_argument("--data", required=True, help="set whose val split's good parts set the blend's two thresholds "
                                                 "and then the threshold (the threshold set of the line as built)")
    p.add_argument("--out", required=True, help="checkpoint to write, path without suffix")
    p.add_argument("--weight", type=float, default=None,
                   help="the window's share of the blend, in (0, 1] (default: the shipped recipe's, "
                        "model.draem.residual.BLEND_WEIGHT; 1: the window alone with its checks)")
    add_max_good_flagged(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from station.evaluation import fit_blend

    print(fit_blend(args.model, args.data, args.out, args.weight, args.max_good_flagged))
    return 0
