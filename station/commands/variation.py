"""``station variation``: add the registered variation model (``model.draem.variation``) to a trained detector.

Fitted on the good parts of ``--data``'s train split, calibrated on the val split's good parts (of ``--val-data``, a
validation set rendered with ``station render --validation``, or else of ``--data``), then the threshold is chosen
on that val split with ``station threshold``'s rule (``model.draem.metrics.choose_threshold``). The networks
are copied unchanged; the sidecar records the fit (``train.variation``: set, manifest hash, parts, blurred copies,
clusters, date). ``--refit`` fits the variation model of a model that has one again (the shipped model on more good
parts, or with ``--blur-copies`` or ``--clusters``).
"""

from __future__ import annotations

import argparse

from model.draem.config import DECISIONS, Alignment
from station.commands.arguments import add_max_good_flagged


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("variation", help="add the registered variation model (fitted on good parts) to a detector")
    p.add_argument("--model", required=True, help="trained checkpoint, path without suffix (e.g. runs/x/best)")
    p.add_argument("--data", required=True, help="set with good parts in its train and val splits (the training set)")
    p.add_argument("--val-data", default=None, metavar="DATA",
                   help="set whose val split calibrates and thresholds (default: --data's; a validation set from "
                        "`station render --validation` has enough good parts for a 1 %% threshold)")
    p.add_argument("--decision", default="variation", choices=DECISIONS,
                   help="which finding rejects: the variation model's alone (variation, default: the shipped recipe; "
                        "station eval still runs and reports the networks, the station skips them) or either "
                        "detector's (combined)")
    p.add_argument("--out", required=True, help="checkpoint to write, path without suffix")
    p.add_argument("--fit-parts", type=int, default=None, metavar="N",
                   help="fit on the first N good train parts only (default: all), to measure how many a line needs")
    p.add_argument("--blur-copies", type=float, default=None, metavar="SIGMA",
                   help="the fit also sees a copy of each good part blurred by up to SIGMA input px, so a softer lens "
                        "or another renderer's pixel filter is among what good parts look like (default: the shipped "
                        "recipe, model.draem.variation.BLUR_COPIES_SIGMA: 1.5; 0: no copies)")
    p.add_argument("--global-polarization", nargs="?", const="mean", default=None, metavar="MODE",
                   choices=[m.value for m in Alignment],
                   help="put each frame's polarization onto the good parts' by one frame-wide DoLP gain and AoLP turn "
                        "before comparing (another renderer's or camera's polarization strength, a polarizer grid "
                        "mounted turned): mean (the default MODE) for every frame, range only for the gain and turn "
                        "beyond the fitted good parts', off not at all (default: the shipped recipe, "
                        "model.draem.variation.GLOBAL_POLARIZATION: range; off for a model without DoLP and AoLP)")
    p.add_argument("--no-global-polarization", dest="global_polarization", action="store_const", const="off",
                   help="the same as --global-polarization off")
    p.add_argument("--clusters", type=int, default=None, metavar="N",
                   help="group the good parts by appearance into up to N clusters (k-means on the appearance "
                        "components' coefficients, at most one per 40 parts) and judge each part against its own "
                        "cluster (default: the shipped recipe, model.draem.variation.APPEARANCE_CLUSTERS: 8; 0: none)")
    p.add_argument("--global-contrast", nargs="?", const="mean", default=None, metavar="MODE",
                   choices=[m.value for m in Alignment],
                   help="divide each frame's log intensity by its frame-wide contrast gain against the good parts' "
                        "(the gain a camera's gamma puts there): mean (the default MODE) all of it, the fitted good "
                        "parts' too; range only the part beyond the good parts' own range; off not at all (default: "
                        "the shipped recipe, model.draem.variation.GLOBAL_CONTRAST: mean)")
    p.add_argument("--contrast-range", dest="global_contrast", action="store_const", const="range",
                   help="the same as --global-contrast range")
    p.add_argument("--no-global-contrast", dest="global_contrast", action="store_const", const="off",
                   help="the same as --global-contrast off")
    p.add_argument("--second-look", action=argparse.BooleanOptionalAction, default=None,
                   help="keep the good parts' left-out residuals in the file and look again at each part above the "
                        "window's 5 %% threshold: test the regions around its map's 5 highest places against them "
                        "(model.draem.second_look; default: the shipped recipe, "
                        "model.draem.variation.SECOND_LOOK)")
    p.add_argument("--second-look-test", action=argparse.BooleanOptionalAction, default=None,
                   help="the second look tests the regions around its map's highest places; without "
                        "(--no-second-look-test) it only gates the parts a look network (station residual "
                        "--second-look) is asked about (default: the shipped recipe, "
                        "model.draem.variation.SECOND_LOOK_TEST)")
    p.add_argument("--curvature", type=float, default=None, metavar="SIGMA",
                   help="the window statistic: each channel's curvature (its signed residual's Laplacian of a "
                        "Gaussian of SIGMA input px), where a dent's faint opposite tilts add up; 0: the box average "
                        "of |z| (default: the shipped recipe, model.draem.variation.CURVATURE_SIGMA)")
    p.add_argument("--judged-priors", default=None, metavar="PRIORS",
                   help="comma-separated priors whose channels the window statistic is taken over; the others are "
                        "read (intensity still registers the part) but not judged: e.g. normal for a judge of a "
                        "deflectometry map alone beside the line's own file (default: all, the shipped recipe)")
    p.add_argument("--smooth-field", action=argparse.BooleanOptionalAction, default=None,
                   help="take a lens's smooth field (its vignetting: a quadratic over the part in log intensity) out "
                        "of every frame's residual, beside the appearance components (model.draem.smooth_field; "
                        "default: the shipped recipe, model.draem.variation.SMOOTH_FIELD: off)")
    p.add_argument("--refit", action="store_true",
                   help="the model already has a variation model: fit it again, networks kept (e.g. the shipped "
                        "model with --blur-copies, or on more good parts)")
    add_max_good_flagged(p)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from station.evaluation import fit_variation

    print(fit_variation(args.model, args.data, args.out, args.max_good_flagged, args.val_data, args.decision,
                        args.fit_parts, args.blur_copies, args.refit, args.global_polarization, args.clusters,
                        args.global_contrast, args.second_look, args.curvature, args.second_look_test,
                        args.judged_priors.split(",") if args.judged_priors is not None else None,
                        args.smooth_field))
    return 0
