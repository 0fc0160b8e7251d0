"""``station threshold``: set a checkpoint's decision threshold on a split of any set with good parts.

``station train`` sets the threshold of ``best`` (the keep-best checkpoint). This sets it for any checkpoint, e.g.
``last`` (the final step, which the published DRAEM keeps), with the same rule (``model.draem.metrics
.choose_threshold``: F1-max on the split's parts, raised so that at most ``--max-good-flagged`` of the good ones
are flagged; with good parts only, that bound alone) and writes it into the checkpoint's sidecar. On another set
than the training set (frames captured at the line, ``station import``) the sidecar records which set and split
set the threshold (``train.threshold_set``). To adapt the input normalisation as well, use ``station adapt``.
"""

from __future__ import annotations

import argparse
import time

from station.errors import UserError


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("threshold", help="set a checkpoint's threshold on a split of any set with good parts")
    p.add_argument("--model", required=True, help="checkpoint path without suffix (e.g. runs/train/x/last)")
    p.add_argument("--data", required=True,
                   help="set with good parts: the training set, or another (rendered or imported) set of the line")
    p.add_argument("--split", default="val", choices=("train", "val", "test"),
                   help="split to choose on (default val; train only on a set the model was not trained on)")
    p.add_argument("--max-good-flagged", type=float, default=0.05,
                   help="at most this fraction of the split's good parts above the threshold (default 0.05)")
    p.set_defaults(func=run)


def set_threshold(model: str, data: str, max_good_flagged: float = 0.05, split: str = "val") -> str:
    """Choose checkpoint ``model``'s threshold on ``data``'s ``split``, write it into its sidecar, and say what it
    does there (one line)."""
    from model.draem.checkpoint import read_sidecar, save_checkpoint
    from model.draem.metrics import choose_threshold
    from station.commands.eval import load_and_evaluate
    from station.datasets import manifest_sha256

    if not 0.0 <= max_good_flagged < 1.0:
        raise UserError(f"--max-good-flagged {max_good_flagged}: a fraction in [0, 1)")
    trained_sha = read_sidecar(model).get("data_manifest_sha256")
    data_sha = manifest_sha256(data)
    same_set = trained_sha == data_sha
    if same_set and split == "train":
        raise UserError(f"{data}: the model was trained on this set's train split; its scores there are not "
                        f"held out: use --split val")
    ck, _, sp, _, ev = load_and_evaluate(model, data, split)
    labels = sp.label.numpy()
    n_bad = int(labels.sum())
    if n_bad == len(labels):
        raise UserError(f"{data}: split {split!r} has no good parts ({n_bad} defective); a threshold needs good "
                        f"parts to bound false rejects")
    choice = choose_threshold(labels, ev.scores, max_good_flagged)
    train = dict(ck.meta.get("train", {}))
    if not same_set:
        train["threshold_set"] = {"data": str(data), "manifest_sha256": data_sha, "split": split,
                                  "n_good": len(labels) - n_bad, "n_defective": n_bad,
                                  "date": time.strftime("%Y-%m-%dT%H:%M:%S")}
    save_checkpoint(model, ck.detector, choice.threshold, choice.rule, trained_sha, ev.metrics, train)
    detected = f" and {choice.detected_fraction:.1%} of defective" if n_bad else " (no defective parts there)"
    where = "" if same_set else " (not its training set: recorded in the sidecar)"
    return (f"{model}: threshold {choice.threshold:.4g} ({choice.rule}); on {len(labels)} {split} parts of "
            f"{data}{where} it flags {choice.flagged_good_fraction:.1%} of good parts{detected}")


def run(args: argparse.Namespace) -> int:
    print(set_threshold(args.model, args.data, args.max_good_flagged, args.split))
    return 0
