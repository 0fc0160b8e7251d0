"""``station split``: the two cameras' thresholds of a station with a second camera (``[second_camera]``), from one
budget of good parts rejected split between them on twin validation sets (``model.draem.camera_split``; the rule of
docs/results/2026-11-30-wide-dome.md). Prints every split and the chosen one, with the two ``station.toml`` lines that
set it, and writes them as JSON with each part's two scores. More good parts allow a larger budget at the same rate
(5 on 725 good twins against 1 on 368): ``--data`` and ``--second-data`` take several twin sets. Neither model file
is changed: a camera's threshold in a split is not its threshold alone."""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from station.commands.arguments import add_max_good_flagged
from station.config import PRESENCE_RULES


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("split", help="set two cameras' thresholds from one budget of good parts rejected")
    p.add_argument("--model", required=True, help="the first camera's checkpoint ([model] path)")
    p.add_argument("--data", required=True, nargs="+", metavar="DIR",
                   help="the first camera's validation set; several sets (other seeds or captures) pool their parts")
    p.add_argument("--second-model", required=True, help="the second camera's checkpoint ([second_camera] model)")
    p.add_argument("--second-data", required=True, nargs="+", metavar="DIR",
                   help="the second camera's twin of each --data set, in the same order (the same seed and parts, "
                        "rendered or captured from it)")
    p.add_argument("--split", default="val", choices=("train", "val", "test"), help="split to choose on (default val)")
    p.add_argument("--presence-rule", default=PRESENCE_RULES[0], choices=PRESENCE_RULES,
                   help="the first camera's [presence] rule (default dolp_contrast)")
    p.add_argument("--second-presence-rule", default=PRESENCE_RULES[1], choices=PRESENCE_RULES,
                   help="the second camera's [second_camera] presence_rule (default row_contrast)")
    add_max_good_flagged(p, "the good parts, by both cameras together")
    p.add_argument("--budget", choices=("expected", "count"), default="expected",
                   help="expected (default, rule 64): hold --max-good-flagged for new good parts on average; each "
                        "camera's threshold adds about one part in n + 1 of its own, so the budget is "
                        "floor(rate (n + 1)) - 2 good parts (1 on 368 good twins at 1 %%); count: floor(rate n) of "
                        "these (3 on 368), which promises more on new parts (docs/second-camera.md)")
    p.add_argument("--out", default=None, metavar="FILE",
                   help="also write the report as JSON, and its picture beside it (FILE with .png: each part's two "
                        "scores and the thresholds)")
    p.set_defaults(func=run)


def format_split(report: dict) -> str:
    """``split_camera_thresholds``'s report as text: a table of the splits, the chosen one and what it promises
    (``model.draem.rate_bounds.either_rate``), the config lines."""
    from model.draem.rate_bounds import either_rate

    held = "of new good parts on average" if report.get("expected") else "of these"
    sets = report["first"]["data"]
    pooled = f" of {len(sets)} twin sets" if isinstance(sets, list) else ""
    lines = [f"{report['parts']} parts{pooled} judged by both cameras ({report['good']} good, {report['defective']} "
             f"defective); budget {report['budget']} good parts ({100 * report['rate']:g} % {held})",
             f"{'k':>3} {'first':>8} {'second':>8} {'good rejected':>14} {'caught':>7}"]
    for i, r in enumerate(report["splits"]):
        mark = "  <- chosen" if i == report["chosen"] else ""
        lines.append(f"{r['k']:>3} {r['first']:>8.4f} {r['second']:>8.4f} {r['good_rejected']:>14} "
                     f"{100 * r['caught']:>6.1f}%{mark}")
    for name, a in report["alone"].items():
        lines.append(f"{name} camera alone at its own threshold {a['threshold']:.4f}: {100 * a['good_rejected']:.1f} % "
                     f"of good parts rejected, {100 * a['caught']:.1f} % of defective caught")
    chosen = report["splits"][report["chosen"]]
    first = report["alone"]["first"]
    if chosen["caught"] <= first["caught"]:
        lines.append(f"the first camera alone catches at least as many here ({100 * first['caught']:.1f} % at "
                     f"{100 * first['good_rejected']:.1f} % of good parts rejected) as the chosen split "
                     f"({100 * chosen['caught']:.1f} % at {100 * chosen['good_rejected'] / report['good']:.1f} %): on "
                     "these parts the second camera does not pay for its share of the budget")
    if report["left_out"]:
        lines.append(f"left out {len(report['left_out'])} parts a camera would not judge (rejected at the station)")
    above, n = report["chosen_good_above"], report["good"]
    mean, bound = either_rate([above["first"], above["second"]], n)
    lines.append(f"chosen split: {chosen['good_rejected']} of {n} good parts rejected (first camera {above['first']}, "
                 f"second {above['second']}); new good parts: at most about {100 * mean:.1f} %, at most "
                 f"{100 * bound:.1f} % at 95 % confidence (each camera's share added; the split is chosen on these "
                 f"parts)")
    lines += ["station.toml:", "[decision]", f"threshold = {config_number(chosen['first'])}", "[second_camera]",
              f"threshold = {config_number(chosen['second'])}"]
    return "\n".join(lines)


def config_number(threshold: float) -> str:
    """A threshold for ``station.toml`` in as few digits as keep its decisions (6 or more): the shortest decimal at
    least ``threshold`` and below the next float32 above it. A split's threshold is a good part's score, which it
    passes (reject when score > threshold); rounded to the nearest 6 digits it could fall below that score, and a
    station set from the printed line would reject the part."""
    from decimal import ROUND_CEILING, Context

    import numpy as np

    above = float(np.nextafter(np.float32(threshold), np.float32(2)))
    for digits in range(6, 18):
        text = f"{Context(prec=digits, rounding=ROUND_CEILING).create_decimal(threshold):f}"
        if threshold <= float(text) < above:
            return text
    return repr(threshold)


def run(args: argparse.Namespace) -> int:
    from station.evaluation import split_camera_thresholds

    report = split_camera_thresholds(args.model, args.data, args.second_model, args.second_data,
                                     args.max_good_flagged, args.split, args.presence_rule, args.second_presence_rule,
                                     args.budget == "expected")
    print(format_split(report))
    if args.out:
        from station.split_plot import plot_split

        Path(args.out).write_text(json.dumps(report, indent=1))
        plot_split(report, Path(args.out).with_suffix(".png"))
    return 0
