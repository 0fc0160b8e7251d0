"""``station threshold``: set a checkpoint's decision threshold on the validation split of the set it trained on.

``station train`` sets the threshold of ``best`` (the keep-best checkpoint). This sets it for any checkpoint, e.g.
``last`` (the final step, which the published DRAEM keeps), with the same rule (``model.draem.metrics
.choose_threshold``: F1-max on the validation parts, raised so that at most 5 % of the good ones are flagged) and
writes it into the checkpoint's sidecar.
"""

from __future__ import annotations

import argparse

from station.errors import UserError


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("threshold", help="set a checkpoint's threshold on its training set's validation split")
    p.add_argument("--model", required=True, help="checkpoint path without suffix (e.g. runs/train/x/last)")
    p.add_argument("--data", required=True, help="the rendered set the checkpoint was trained on")
    p.add_argument("--max-good-flagged", type=float, default=0.05,
                   help="at most this fraction of good validation parts above the threshold")
    p.set_defaults(func=run)


def set_threshold(model: str, data: str, max_good_flagged: float = 0.05) -> str:
    """Choose checkpoint ``model``'s threshold on ``data``'s validation split, write it into its sidecar, and say
    what it does there (one line)."""
    from model.draem.checkpoint import save_checkpoint
    from model.draem.metrics import choose_threshold
    from station.commands.eval import load_and_evaluate
    from station.commands.train import check_trained_on

    if not 0.0 <= max_good_flagged < 1.0:
        raise UserError(f"--max-good-flagged {max_good_flagged}: a fraction in [0, 1)")
    sha = check_trained_on(model, data)  # before loading the split and running the model
    ck, _, sp, _, ev = load_and_evaluate(model, data, "val")
    labels = sp.label.numpy()
    if not 0 < int(labels.sum()) < len(labels):
        raise UserError(f"{data}: split 'val' needs good and defective parts to set a threshold "
                        f"({int(labels.sum())} of {len(labels)} defective)")
    choice = choose_threshold(labels, ev.scores, max_good_flagged)
    save_checkpoint(model, ck.detector, choice.threshold, choice.rule, sha, ev.metrics, ck.meta.get("train", {}))
    return (f"{model}: threshold {choice.threshold:.4g} ({choice.rule}); on {len(labels)} validation parts it "
            f"flags {choice.flagged_good_fraction:.1%} of good parts and {choice.detected_fraction:.1%} of defective")


def run(args: argparse.Namespace) -> int:
    print(set_threshold(args.model, args.data, args.max_good_flagged))
    return 0
