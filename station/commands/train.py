"""``station train``: train the DRAEM detector on a dataset (sim's format: rendered by ``station render`` or
imported by ``station import``) through the priors core.

Bridge (``station.datasets.load_split``): ``sim.dataset`` sample -> ``model.priors.compute_priors`` on the raw
mosaic (what the camera would give) -> stacked prior channels -> the region of interest -> network input size ->
``model.draem``. The training frames' brightness statistics go into every checkpoint (``train.frame_statistics``).
The normal prior comes from a learned normal estimator (``--normal-net``, ``model.normals.estimator``), copied
beside the checkpoint so the station computes the same normals; without one, from the renderer's ground-truth
normals (a research upper bound that a station cannot run; stated in every report).
"""

from __future__ import annotations

import argparse
import json
import logging
from pathlib import Path
from typing import TYPE_CHECKING, Any

from model.draem.config import ROIS
from model.draem.runtime import TRAIN_PRECISIONS
from station.commands.arguments import positive_int, positive_minutes, seed
from station.datasets import (
    dome_segments_of,
    fov_of,
    frame_aspect_of,
    good_part_of,
    load_split,
    manifest_sha256,
    rendered_defects,
    subset,
)
from station.errors import UserError

if TYPE_CHECKING:
    from model.normals.estimator import NormalEstimator

log = logging.getLogger(__name__)



def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("train", help="train the DRAEM detector on a rendered or imported set (checkpoints, keep-best)")
    p.add_argument("--data", required=True, help="dataset folder (station render --out, or station import --out)")
    p.add_argument("--val-data", default=None, metavar="DATA",
                   help="set whose val split keep-best and the threshold read (default: --data's; a validation set "
                        "from `station render --validation`, for a training set rendered without a val split)")
    p.add_argument("--priors", default="intensity",
                   help="comma-separated, of intensity,dolp,aolp,normal (the default is the shipped model's; "
                        "polarization: intensity,dolp,aolp; the paper's adds normal)")
    p.add_argument("--preset", default="fast",
                   help="network preset: paper (128/64 @ 256), fast (32/16 @ 128), lean (16/16 @ 128), tiny")
    p.add_argument("--fusion", default="fused", choices=("ensemble", "fused"),
                   help="fused: one DRAEM over all priors (the shipped model); ensemble: one per prior, averaged (the "
                        "paper)")
    p.add_argument("--roi", default="center", choices=ROIS,
                   help="center: the centre square of the frame (a part anywhere in it, as an imported set's); "
                        "band: the middle half of that square at up to twice its detail (input SIZE x 2 SIZE; a part "
                        "laid across the view: the shipped model's, with --size 96); "
                        "tall: its middle two thirds at the band's detail (input SIZE x 1.5 SIZE, SIZE a multiple "
                        "of 64: room for a turned camera, at a cost in defects caught; a variation model's frame "
                        "around the view does it without the cost up to 5 degrees); "
                        "frame: the whole frame resized "
                        "(no crop, for comparison); object: square around the rendered object mask (needs ground "
                        "truth at inference: research upper bound)")
    p.add_argument("--normal-net", default=None,
                   help="learned normal estimator (station normals --out .../normal_net) for the normal prior; "
                        "without it the rendered ground-truth normals are used (research only: a station refuses)")
    p.add_argument("--size", type=positive_int, default=None,
                   help="input size in pixels (multiple of 32; default: preset's)")
    p.add_argument("--steps", type=positive_int, default=2000, help="optimiser steps")
    p.add_argument("--batch-size", type=int, default=8)
    p.add_argument("--eval-every", type=int, default=250, help="steps between held-out evaluation + checkpoint")
    p.add_argument("--seed", type=seed, default=0)
    p.add_argument("--device", default="auto", help="auto (CUDA if available), cpu, cuda, cuda:1, ...")
    p.add_argument("--precision", default="auto", choices=TRAIN_PRECISIONS,
                   help="auto: fp32 on CPU (bf16 measured slower on AVX2 CPUs), bf16 autocast on CUDA")
    p.add_argument("--rendered-fraction", type=float, default=0.0, metavar="F",
                   help="share of each batch taken from the training split's rendered defective parts with their "
                        "true masks (mixed supervision; the rest keeps DRAEM's synthetic anomalies); 0 = the paper's "
                        "recipe; needs a set rendered with defects in its train split (default 0)")
    p.add_argument("--polarization-noise", type=float, default=0.0, metavar="SIGMA",
                   help="add Stokes noise up to SIGMA (units of S0; a random level per sample) to the training "
                        "inputs, so that a line's noise level (exposure, gain; a renderer's samples per pixel), "
                        "which raises DoLP, is not taken for a defect; 0 = none (default 0)")
    p.add_argument("--holdout-type", default=None, metavar="TYPE",
                   help="leave this defect type out of the rendered training defects, to evaluate the model on a "
                        "kind of defect it never saw (station eval marks it); default: none left out")
    p.add_argument("--init", default=None, metavar="MODEL",
                   help="start from this checkpoint (path without suffix, same priors, fusion and preset; roi and "
                        "size may differ) with a fresh optimiser: e.g. fine-tune a model trained on good parts with "
                        "--rendered-fraction")
    p.add_argument("--stop-at-step", type=int, default=None, metavar="N",
                   help="stop after step N of the --steps schedule (a checkpoint is written); rerun with a later N, "
                        "or without, to go on with the same schedule")
    p.add_argument("--max-minutes", type=positive_minutes, default=None, help="stop after this much training time")
    p.add_argument("--limit", type=positive_int, default=None, help="use at most N samples per split (smoke runs)")
    p.add_argument("--out", default=None, help="output folder (default runs/train/<preset>-<fusion>)")
    p.add_argument("--no-resume", action="store_true", help="start over even if the output folder has a checkpoint")
    p.set_defaults(func=run)


def val_set(data: str, val_data: str | None) -> str:
    """The set whose val split keep-best and the threshold read: ``val_data``, else ``data``; UserError in one line
    when it has none (a training set rendered without one: say how)."""
    from sim.dataset import open_dataset
    from sim.errors import SimError

    root = val_data or data
    try:
        has_val = bool(open_dataset(root).indices("val"))
    except SimError as exc:
        raise UserError(f"--val-data {exc}" if val_data else str(exc)) from None
    if not has_val:
        hint = "" if val_data else (" (keep-best reads a val split: give --val-data, a set rendered with `station "
                                    "render --validation`)")
        raise UserError(f"{'--val-data ' if val_data else ''}{root}: no complete samples in split 'val'{hint}")
    return root


def dataset_fov_x_deg(root: str | Path) -> float | None:
    """The horizontal field of view (degrees) of a rendered set's camera (its first sample's); None if unknown."""
    from sim.dataset import open_dataset

    ds = open_dataset(root)
    idx = ds.indices()
    return fov_of(ds.load(idx[0], ground_truth=False).params) if idx else None


def normal_estimator(path: str | None, data: str | Path, out: Path) -> NormalEstimator | None:
    """The learned normal estimator at ``path`` for frames of the set ``data``, copied to ``out/normal_net`` (the
    checkpoint's companion); None (ground truth) without ``path``."""
    if path is None:
        log.warning("normal prior from the rendered ground truth (no --normal-net): a research upper bound; the "
                    "station refuses such a model")
        return None
    from model.draem.distributed import from_env
    from model.normals.estimator import BESIDE_CHECKPOINT, NormalEstimator
    from model.normals.net import copy_normal_net

    if not from_env().is_main:  # torchrun: rank 0 alone writes the copy, the other ranks read the source
        return NormalEstimator.load(path, dataset_fov_x_deg(data))
    copy_normal_net(path, out / BESIDE_CHECKPOINT)
    return NormalEstimator.load(out / BESIDE_CHECKPOINT, dataset_fov_x_deg(data))


def normal_prior_record(normals: NormalEstimator | None) -> dict:
    from model.normals.estimator import describe

    return describe(normals)


def init_record(path: str) -> dict[str, Any]:
    """What ``--init`` started from, for the sidecar's ``train.init``: its path, weights hash and what it was
    trained with (so a held-out type can be checked to be absent from the whole history)."""
    from model.draem.checkpoint import CheckpointError, read_sidecar

    try:  # the sidecar only: train() loads the weights, and checks the model config, once
        meta = read_sidecar(path)
    except (CheckpointError, OSError) as exc:
        raise UserError(f"--init {path}: {exc}") from None
    train_meta = meta.get("train") or {}
    return {"path": str(path), "weights_sha256": meta.get("weights_sha256"), "step": train_meta.get("step"),
            "rendered_defects": train_meta.get("rendered_defects"), "init": train_meta.get("init")}


def check_init_holds_out(record: dict[str, Any] | None, holdout_type: str | None) -> None:
    """UserError when a model in ``--init``'s history trained on rendered defects of ``holdout_type`` (it would
    not be held out)."""
    while holdout_type and record:
        rd = record.get("rendered_defects") or {}
        if rd.get("fraction") and rd.get("holdout_type") != holdout_type:
            raise UserError(f"--init {record['path']}: trained on rendered defects with "
                            f"{rd.get('holdout_type') or 'no type'} held out, so {holdout_type} would not be held "
                            f"out; start from a model trained without rendered {holdout_type} defects")
        record = record.get("init")


def run(args: argparse.Namespace) -> int:
    from model.draem.checkpoint import load_checkpoint, save_checkpoint
    from model.draem.config import ModelConfig, check_priors
    from model.draem.errors import ConfigError, ModelError
    from model.draem.evaluate import EvalData, evaluate, synthetic_eval_data
    from model.draem.metrics import choose_threshold
    from model.draem.train import TensorData, TrainConfig, train
    from model.priors.frame_stats import StatisticsRange

    priors = check_priors(args.priors)
    try:
        config = ModelConfig.from_preset(args.preset, priors, args.fusion, args.size, args.roi,
                                         dome_segments_of(args.data)).with_(frame_aspect=frame_aspect_of(args.data))
    except ModelError as exc:
        raise UserError(f"--priors {args.priors} with --data {args.data}: {exc}") from None
    out = Path(args.out or f"runs/train/{args.preset}-{args.fusion}")
    size = config.input_shape
    normals = normal_estimator(args.normal_net, args.data, out) if "normal" in priors else None
    normal_prior = normal_prior_record(normals) if "normal" in priors else None
    mixed = args.rendered_fraction > 0
    if args.holdout_type and not mixed:
        raise UserError("--holdout-type leaves a type out of the rendered training defects: it needs "
                        "--rendered-fraction > 0")
    val_root = val_set(args.data, args.val_data)  # before minutes of loading
    tr = load_split(args.data, "train", priors, size, args.limit, good_only=not mixed, roi=config.roi,
                    normals=normals, frame_aspect=config.frame_aspect,
                    dome_segments=config.dome_segments)
    defects, learned = rendered_defects(tr, args.holdout_type, args.data) if mixed else (None, ())
    if mixed:
        tr = good_part_of(tr)
    va = load_split(val_root, "val", priors, size, args.limit, roi=config.roi, normals=normals,
                    frame_aspect=config.frame_aspect, dome_segments=config.dome_segments)
    if args.holdout_type:  # keep-best and the threshold must not see the type held out either
        va = subset(va, [i for i, t in enumerate(va.defect_type) if t != args.holdout_type])
    log.info("train: %d good samples; val: %d samples (%d with defects); input %dx%d; normals: %s",
             len(tr.index), len(va.index), int(va.label.sum()), size[1], size[0],
             (normal_prior or {}).get("source", "not used"))
    rendered = EvalData(va.priors, va.object_mask, va.defect_mask, va.label, "rendered", va.mask_known)
    defective = int(va.label.sum())
    if defective == len(va.index):  # keep-best's synthetic anomalies need good parts to sit on
        raise UserError(f"{val_root}: its val split has no good part ({defective} defective): keep-best "
                        "needs good parts; render more parts, or give --val-data a validation set")
    has_both = defective > 0
    val = rendered if has_both else synthetic_eval_data(
        TensorData(va.priors[va.label == 0], va.object_mask[va.label == 0]), priors, seed=args.seed + 1)
    if not has_both:
        log.warning("val split lacks rendered defects or good parts: keep-best uses synthetic anomalies")
    try:
        tc = TrainConfig(steps=args.steps, batch_size=args.batch_size, seed=args.seed, eval_every=args.eval_every,
                         device=args.device, precision=args.precision, max_minutes=args.max_minutes,
                         stop_at_step=args.stop_at_step,
                         rendered_fraction=args.rendered_fraction, polarization_noise=args.polarization_noise)
    except ConfigError as exc:
        flag = f"--{exc.key.replace('_', '-')} {getattr(args, exc.key)}"
        if exc.key == "rendered_fraction":
            flag += f" with --batch-size {args.batch_size}"
        raise UserError(f"{flag}: {exc}") from None
    sha = manifest_sha256(args.data)
    meta: dict[str, Any] = {"frame_statistics": StatisticsRange.from_frames(tr.frame_stats).to_dict()}
    if args.val_data:
        meta["val_data"] = {"data": str(args.val_data), "manifest_sha256": manifest_sha256(args.val_data)}
    if normal_prior:
        meta["normal_prior"] = normal_prior
    if defects is not None:
        meta["rendered_defects"] = {"fraction": args.rendered_fraction, "parts": len(defects),
                                    "holdout_type": args.holdout_type, "types": list(learned)}
    if args.polarization_noise:
        meta["polarization_noise"] = args.polarization_noise
    if args.init:
        meta["init"] = init_record(args.init)
        check_init_holds_out(meta["init"], args.holdout_type)
    res = train(config, TensorData(tr.priors, tr.object_mask), out, tc, val, resume=not args.no_resume,
                data_manifest_sha256=sha, train_meta=meta, defects=defects, init=args.init)
    if not res.is_main:  # torchrun: rank 0 alone evaluates, sets the threshold and writes the summary
        return 0
    ck = load_checkpoint(out / "best")
    ev = evaluate(ck.detector, rendered if has_both else val)
    choice = choose_threshold((rendered if has_both else val).label.numpy(), ev.scores)
    save_checkpoint(out / "best", ck.detector, choice.threshold, choice.rule, sha, ev.metrics,
                    {**ck.meta.get("train", {}), **meta, "normal_prior": normal_prior})
    summary = {"best": str(res.best_path), "steps": res.steps_done, "seconds": round(res.seconds, 1),
               "val_kind": val.kind, "val_parts": len(va.index), "val_defective": int(va.label.sum()),
               "threshold": choice.threshold, "threshold_rule": choice.rule,
               "flagged_good_fraction": choice.flagged_good_fraction, "detected_fraction": choice.detected_fraction,
               **{k: v for k, v in ev.metrics.items() if isinstance(v, float)}}
    (out / "train_summary.json").write_text(json.dumps(summary, indent=1))
    print(json.dumps(summary, indent=1))
    return 0
