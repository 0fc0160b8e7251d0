"""``station ensemble``: the paper's per-prior ensemble assembled from single-prior models trained apart
(``station train --priors <one> --fusion fused``, one per machine, GPU or night), with its threshold set on the
validation split of the set they all trained on. ``station eval --ablation`` then reads it like a trained ensemble.

The sidecar records each member's checkpoint and weights hash (``train.assembled_from``); a learned normal
estimator is copied beside the ensemble, as ``station train`` does.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from station.commands.arguments import add_max_good_flagged
from station.errors import UserError

if TYPE_CHECKING:
    from model.draem.checkpoint import Checkpoint


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("ensemble", help="assemble a per-prior ensemble from single-prior models trained apart")
    p.add_argument("--members", required=True,
                   help="comma-separated checkpoints (without suffix), each over one prior, all trained on --data")
    p.add_argument("--data", required=True, help="the rendered set the members trained on (threshold: its val split)")
    p.add_argument("--out", required=True, help="checkpoint to write, without suffix (e.g. runs/train/ens/last)")
    add_max_good_flagged(p, "the good validation parts")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from model.draem.assemble import assemble_ensemble
    from model.draem.checkpoint import load_checkpoint, paths, save_checkpoint
    from model.draem.errors import ModelError
    from station.datasets import check_trained_on
    from station.evaluation import set_threshold

    members = [m.strip() for m in args.members.split(",") if m.strip()]
    if len(members) < 2:
        raise UserError(f"--members {args.members!r}: at least two checkpoints")
    out = paths(args.out)[1].with_suffix("")
    if any(paths(m)[1].with_suffix("").resolve() == out.resolve() for m in members):
        raise UserError(f"--out {args.out}: would overwrite one of the members")
    sha = {check_trained_on(m, args.data) for m in members}  # every member on this very set, before loading any
    cks = [load_checkpoint(m) for m in members]
    try:
        detector = assemble_ensemble([c.detector for c in cks], members)
    except ModelError as exc:
        raise UserError(str(exc)) from None
    given = {p: (m, c) for m, c in zip(members, cks, strict=True) for p in c.detector.config.priors}
    train: dict = {"assembled_from": {p: {"model": m, "weights_sha256": c.meta["weights_sha256"],
                                          "step": c.meta.get("train", {}).get("step")} for p, (m, c) in given.items()}}
    if "normal" in given:
        train["normal_prior"] = _copy_normal_prior(*given["normal"], out)
    save_checkpoint(out, detector, None, "", next((s for s in sha if s), None), train=train)
    print(f"wrote {out}.pt / .json: ensemble over {', '.join(detector.config.priors)}")
    print(set_threshold(str(out), args.data, args.max_good_flagged))
    return 0


def _copy_normal_prior(member: str, ck: Checkpoint, out: Path) -> dict:
    """The normal member's ``normal_prior`` record, its learned estimator copied beside ``out`` (as train does)."""
    from model.draem.checkpoint import paths
    from model.normals.estimator import BESIDE_CHECKPOINT as NORMAL_NET_FILE
    from model.normals.estimator import copy_beside

    rec = (ck.meta.get("train") or {}).get("normal_prior")
    if not rec:
        raise UserError(f"{member}: reads the normal prior but does not record how it was made (train.normal_prior)")
    if rec.get("source") != "learned":
        return rec
    copy_beside(paths(member)[1], out, rec)  # an ensemble in the normal member's folder shares its copy
    return {**rec, "file": NORMAL_NET_FILE + ".json"}
