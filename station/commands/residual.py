"""``station residual``: add residual networks (``model.draem.residual``) that read the variation model's signed z
maps, and let them decide, or (``--second-look``) ask them about the parts above the variation model's gate.

Trained on ``--data``'s train split (its good parts' left-out residuals, half of them with synthetic anomalies, and
its rendered defective parts with their masks, and those of each ``--more-defects`` set; ``--holdout-type`` leaves
one type's out), calibrated and thresholded on ``--val-data``'s val split with ``station threshold``'s rule. The
networks and the variation model are copied (the variation model fitted again on the same good parts: the same
fit); the sidecar records the training (``train.residual``). ``--lens-copies`` adds a lens copy of each good part
(``model.draem.lens_copies``).
"""

from __future__ import annotations

import argparse

from station.commands.arguments import add_max_good_flagged, number_range, seed


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("residual", help="add residual networks (trained on the variation model's residuals) to a "
                                        "detector with a variation model: a second look beside it "
                                        "(--second-look, the shipped recipe) or the decision")
    p.add_argument("--model", required=True, help="checkpoint with a variation model, path without suffix")
    p.add_argument("--data", required=True, help="the training set: good and rendered defective parts in its train "
                                                 "split (station render --defects-in-train)")
    p.add_argument("--val-data", default=None, metavar="DATA",
                   help="set whose val split calibrates and thresholds (default: --data's)")
    p.add_argument("--out", required=True, help="checkpoint to write, path without suffix")
    p.add_argument("--members", type=int, default=3, help="networks, each with its own seed; their scores averaged")
    p.add_argument("--steps", type=int, default=3000, help="training steps per network (about 0.15 s each on 2 "
                                                           "cores)")
    p.add_argument("--seed", type=seed, default=0, help="seed of the first network (the next ones count up)")
    p.add_argument("--holdout-type", default=None, metavar="TYPE",
                   help="leave this defect type's rendered parts out of training, to measure a kind of defect the "
                        "networks never saw (default: none left out)")
    add_max_good_flagged(p)
    p.add_argument("--more-defects", action="append", default=[], metavar="DATA",
                   help="another rendered set whose defective train parts the networks also learn from (its good "
                        "parts are not used); repeat for several (e.g. station render --defects 1 "
                        "--defects-in-train with its own seed)")
    p.add_argument("--second-look", action="store_true",
                   help="the networks do not decide: they are the variation model's second look at parts above its "
                        "gate, side by side with its score at each one's own 1 %% threshold (the shipped recipe; "
                        "needs a model with the second look)")
    p.add_argument("--lens-copies", type=number_range("--lens-copies", "[0, 1) (e.g. 0,0.3)"), default=None,
                   metavar="LO,HI",
                   help="also train on a lens copy of each good part: the part as a lens losing LO to HI of the light "
                        "at the frame's corners (drawn per copy) would show it, so that a lens's smooth fall is no "
                        "defect (model.draem.lens_copies; default: none)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from station.evaluation import fit_residual

    print(fit_residual(args.model, args.data, args.out, args.val_data, args.members, args.steps, args.seed,
                       args.holdout_type, args.max_good_flagged, args.second_look, args.more_defects,
                       args.lens_copies))
    return 0
