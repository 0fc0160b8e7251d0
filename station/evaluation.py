"""Evaluating a checkpoint on a dataset split as the station feeds it: the split at the model's roi, input size and
normal prior, the network that runs it (torch fp32, or the int8 networks of ``station quantize``), the evaluation.
Shared by ``station eval``, ``threshold``, ``ensemble``, ``quantize``, ``adapt`` and the pipeline benchmark;
``set_threshold`` is ``station threshold``'s rule, ``split_camera_thresholds`` ``station split``'s, ``pick_draw``
``station pick``'s."""

from __future__ import annotations

import json
import math
import shutil
import time
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from model.draem.config import GOOD_REJECTED_RATE
from station.config import PRESENCE_RULES
from station.errors import UserError

if TYPE_CHECKING:
    from model.draem.outline_check import OutlineCheck

ABLATION = (("R", ("intensity",)), ("R+AoLP", ("intensity", "aolp")), ("R+AoLP+DoLP", ("intensity", "aolp", "dolp")),
            ("all", ("intensity", "aolp", "dolp", "normal")))
"""The paper's ablation: members of a per-prior ensemble averaged, growing from unpolarized intensity (R)."""


def normal_prior_record(ck) -> dict | None:
    """The checkpoint's record of how its normal prior was made (None without a normal input)."""
    return ck.meta.get("train", {}).get("normal_prior") if "normal" in ck.detector.config.priors else None


def model_split(ck, model: str, data: str | Path, split: str, limit: int | None = None, good_only: bool = False,
                presence=None):
    """``data``'s split (only its good parts with ``good_only``) as checkpoint ``ck`` (loaded from ``model``) sees
    it at the station: its roi, its input size, its learned normal prior; ``presence`` (a
    ``station.presence.PresenceCheck``, default the station's default) marks the frames the station would not
    judge. The frame around each view comes along as the station reads it (``ModelConfig.around_px``). Returns
    ``station.datasets.SplitTensors``."""
    from station.datasets import load_split

    cfg = ck.detector.config
    normal_prior = normal_prior_record(ck)
    if "normal" in cfg.priors and not normal_prior:
        raise UserError(f"{model}: the model reads the normal prior but its sidecar does not record how that was made "
                        f"(train.normal_prior; `last` checkpoints before 2026-11-23 lack it: copy it from `best`)")
    normals = None
    if normal_prior and normal_prior.get("source") == "learned":
        from model.draem.checkpoint import paths
        from model.normals.estimator import load_for_checkpoint

        normals = load_for_checkpoint(paths(model)[1], normal_prior)
    return load_split(data, split, cfg.priors, cfg.input_shape, limit, good_only=good_only, roi=cfg.roi,
                      normals=normals, frame_aspect=cfg.frame_aspect, dome_segments=cfg.dome_segments,
                      presence=presence, around_px=cfg.around_px)


def without_held_out_type(sp, train: Mapping):
    """The split ``sp`` without the defective parts of the type the sidecar record ``train`` held out of training
    (``model.draem.holdout.held_out_type``): a threshold or calibration chosen on them would have seen that type."""
    from model.draem.holdout import held_out_type, indices_without_type
    from station.datasets import subset

    held = held_out_type(train)
    if held is None:
        return sp
    try:
        keep = indices_without_type(sp.defect_type, held)
    except ValueError:  # the split has no part of that type: nothing to leave out
        return sp
    return subset(sp, keep.tolist())


def inference_net(ck, model: str, precision: str):
    """What runs the checkpoint (``model.draem.predictor.inference_network``: its torch detector, "fp32", or its
    int8 networks from ``station quantize``, "int8"), the model's error as the station's one-line ``UserError``."""
    from model.draem.errors import ModelError
    from model.draem.predictor import inference_network

    try:
        return inference_network(ck, model, precision)
    except ModelError as exc:
        raise UserError(str(exc)) from None


def load_and_evaluate(model: str, data: str | Path, split: str, limit: int | None = None, precision: str = "fp32",
                      presence=None):
    """Checkpoint ``model`` on ``data``'s split, as the station feeds it (``model_split``, with ``presence``), run at
    ``precision``: (checkpoint, the network that ran it (``inference_net``), split tensors, EvalData, evaluation)."""
    from model.draem.checkpoint import load_checkpoint

    ck = load_checkpoint(model)
    net = inference_net(ck, model, precision)
    return ck, net, *evaluate_split(ck, net, model, data, split, limit, presence)


def evaluate_split(ck, net, model: str, data: str | Path, split: str, limit: int | None = None, presence=None):
    """A loaded checkpoint ``ck`` (from ``model``) and the network that runs it on another split of ``data``:
    (split tensors, EvalData, evaluation), without loading the model again."""
    sp = model_split(ck, model, data, split, limit, presence=presence)
    return sp, *evaluate_tensors(net, sp)


def evaluate_tensors(net, sp):
    """Split tensors ``sp`` (``station.datasets.SplitTensors``) run through ``net``: (EvalData, evaluation)."""
    from model.draem.evaluate import EvalData, evaluate

    tensors = EvalData(sp.priors, sp.object_mask, sp.defect_mask, sp.label, "rendered", sp.mask_known, sp.around)
    return tensors, evaluate(net, tensors)


def check_max_good_flagged(value: float) -> None:
    """UserError unless ``--max-good-flagged`` is a fraction in [0, 1)."""
    if not 0.0 <= value < 1.0:
        raise UserError(f"--max-good-flagged {value}: a fraction in [0, 1)")


def set_threshold(model: str, data: str | Sequence[str], max_good_flagged: float = GOOD_REJECTED_RATE,
                  split: str = "val", presence_rule: str = PRESENCE_RULES[0], confidence: float | None = None) -> str:
    """Choose checkpoint ``model``'s threshold on ``data``'s ``split``, write it into its sidecar, and say what it
    does there (one line). Several sets (other seeds, or captures on other days) pool their parts; a set named twice
    is refused. Frames the station would not judge are left out, with the presence check's ``presence_rule``
    (``station.presence.PresenceRule``: the one the camera's ``[presence]`` uses) at its defaults. ``confidence``:
    ``max_good_flagged`` is promised for new good parts at that confidence, not counted on these
    (``metrics.choose_threshold``). A model with a variation member also takes the good parts' median turn as the
    centre each part's turn is read from (``VariationModel.calibrate_turn``: the line's operating point)."""
    from model.draem.checkpoint import load_checkpoint, read_sidecar, save_checkpoint
    from model.draem.metrics import choose_threshold
    from station.datasets import concat, manifest_sha256

    check_max_good_flagged(max_good_flagged)
    sets = _set_list(data, "--data")
    trained_sha = read_sidecar(model).get("data_manifest_sha256")
    shas = [manifest_sha256(d) for d in sets]
    trained_on = [d for d, sha in zip(sets, shas, strict=True) if sha == trained_sha]
    if trained_on and split == "train":
        raise UserError(f"{trained_on[0]}: the model was trained on this set's train split; its scores there are not "
                        f"held out: use --split val")
    ck = load_checkpoint(model)
    parts, left_out = [], {}
    for j, (sp, lo) in enumerate(_judged_splits(ck, model, sets, split, presence_rule)):
        parts.append(sp)
        left_out.update({_sample_key(j, i, len(sets) > 1): why for i, why in lo.items()})
    name = ", ".join(sets)
    if not any(p.index for p in parts):
        raise UserError(f"{name}: the station would judge none of split {split!r}'s frames "
                        f"({describe_left_out(left_out)})")
    sp = concat([p for p in parts if p.index])
    _, ev = evaluate_tensors(inference_net(ck, model, "fp32"), sp)
    labels = sp.label.numpy()
    n_bad = int(labels.sum())
    if n_bad == len(labels):
        raise UserError(f"{name}: split {split!r} has no good parts ({n_bad} defective); a threshold needs good "
                        f"parts to bound false rejects")
    try:
        choice = choose_threshold(labels, ev.scores, max_good_flagged, confidence)
    except ValueError as exc:
        raise UserError(f"{name}: split {split!r}: {exc}") from None
    n_good, good_flagged = len(labels) - n_bad, int((ev.scores[labels == 0] > choice.threshold).sum())
    turn = ""
    if ck.detector.variation is not None:  # where the line's good parts lie turned: 0 of each part's turn_deg
        good = labels == 0
        arounds = None if sp.around is None else list(sp.around[good].float().numpy())
        centre = ck.detector.variation.calibrate_turn(sp.priors[good].float().numpy(), arounds)
        turn = f"; its good parts' median turn {centre:+.2f} degrees from the reference"
    train = dict(ck.meta.get("train", {}))
    others = len(trained_on) < len(sets)
    if others:
        one = len(sets) == 1
        train["threshold_set"] = {"data": sets[0] if one else sets, "manifest_sha256": shas[0] if one else shas,
                                  "split": split, "n_good": n_good, "n_good_flagged": good_flagged,
                                  "n_defective": n_bad, "left_out": {str(i): why for i, why in left_out.items()},
                                  "presence_rule": str(presence_rule), "date": time.strftime("%Y-%m-%dT%H:%M:%S")}
    save_checkpoint(model, ck.detector, choice.threshold, choice.rule, trained_sha, ev.metrics, train)
    detected = f" and {choice.detected_fraction:.1%} of defective" if n_bad else " (no defective parts there)"
    where = ("" if not others else " (not its training set: recorded in the sidecar)" if len(sets) == 1
             else f" ({len(sets)} sets pooled; recorded in the sidecar)")
    skipped = (f"\nleft out {len(left_out)} frames the station would not judge: {describe_left_out(left_out)}"
               if left_out else "")
    return (f"{model}: threshold {choice.threshold:.4g} ({choice.rule}); on {len(labels)} {split} parts of "
            f"{name}{where} it flags {choice.flagged_good_fraction:.1%} of good parts "
            f"({new_good_rate(good_flagged, n_good)}){detected}{turn}{skipped}")


def pick_draw(models: Sequence[str], data: str, out: str, split: str = "val",
              presence_rule: str = PRESENCE_RULES[0]) -> str:
    """Of ``models`` (trainings of one recipe, each with its stored threshold), copy to ``out`` the one
    ``model.draem.draw_choice.RULE`` keeps on ``data``'s ``split`` as the station would judge it (e.g. the validation
    parts seen through a lens); ``out``'s sidecar records every draw's counts (``train.draw_choice``). Returns one
    line per draw and the choice."""
    from model.draem.checkpoint import copy_checkpoint, load_checkpoint
    from model.draem.draw_choice import RULE, choose_draw, draw_counts
    from station.datasets import manifest_sha256

    if len(models) < 2:
        raise UserError(f"--models: a choice needs at least two files, got {len(models)}")
    if len(set(models)) < len(models):
        raise UserError("--models: a file is named twice")
    if out in models:
        raise UserError(f"--out {out}: one of the candidates; write the choice elsewhere")
    cks = {m: load_checkpoint(m) for m in models}  # every file's errors before minutes of scoring
    for m, ck in cks.items():
        if ck.threshold is None:
            raise UserError(f"{m}: no stored threshold (station threshold); each draw is judged at its own")
    counts = []
    for m, ck in cks.items():
        (sp, _), = _judged_splits(ck, m, [data], split, presence_rule)
        if not sp.index:
            raise UserError(f"{data}: the station would judge none of split {split!r}'s frames for {m}")
        _, ev = evaluate_tensors(inference_net(ck, m, "fp32"), sp)
        counts.append(draw_counts(m, float(ck.threshold), sp.label.numpy(), ev.scores))
    try:
        choice = choose_draw(counts)
    except ValueError as exc:
        raise UserError(f"{data}: split {split!r}: {exc}") from None
    copy_checkpoint(choice.kept_name, out, train={"draw_choice": {
        "data": data, "manifest_sha256": manifest_sha256(data), "split": split, "rule": RULE,
        "presence_rule": str(presence_rule), "kept": choice.kept_name,
        "draws": [vars(c) for c in choice.counts], "date": time.strftime("%Y-%m-%dT%H:%M:%S")}})
    lines = [c.line() for c in choice.counts]
    return "\n".join([*lines, f"kept: {choice.kept_name} ({RULE}) -> {out}"])


def _judged_splits(ck, model: str, sets: Sequence[str], split: str,
                   presence_rule: str) -> Iterator[tuple[Any, dict[int, str]]]:
    """Each set's ``split`` in turn as the station would judge it (``judged_part_of``, with the presence rule
    ``presence_rule``), without the type the model held out of training, and the unjudged samples' reasons."""
    from station.datasets import judged_part_of
    from station.presence import PresenceCheck

    for data in sets:
        sp, unjudged = judged_part_of(model_split(ck, model, data, split, presence=PresenceCheck(rule=presence_rule)))
        yield without_held_out_type(sp, ck.meta.get("train", {})), unjudged


def _sample_key(j: int, i: int, pooled: bool) -> str:
    """A sample's name in a report: its index, or ``set:index`` when several sets are pooled."""
    return f"{j}:{i}" if pooled else str(i)


def _set_list(data: str | Path | Sequence[str], option: str) -> list[str]:
    """One or several sets as a list of paths. A set named twice, or two rendered sets of one seed (the same parts),
    would count their parts twice: refused."""
    from sim.dataset import open_dataset

    sets = [str(d) for d in ([data] if isinstance(data, str | Path) else data)]
    if not sets:
        raise UserError(f"{option}: name a set")
    paths = [Path(d).resolve() for d in sets]
    if len(set(paths)) < len(paths):
        raise UserError(f"{', '.join(sets)}: a set is named twice; its parts would count twice")
    if len(sets) > 1:
        seeds = [open_dataset(d).manifest.get("seed") for d in sets]
        same = [d for d, s in zip(sets, seeds, strict=True) if s is not None and seeds.count(s) > 1]
        if same:
            raise UserError(f"{', '.join(same)}: the same seed ({seeds[sets.index(same[0])]}) holds the same parts; "
                            "pool sets of other seeds")
    return sets


def new_good_rate(k: int, n: int) -> str:
    """What a threshold that ``k`` of ``n`` good validation parts lie above says of new good parts
    (``model.draem.rate_bounds``): their expected share rejected and its 95 % bound."""
    from model.draem.rate_bounds import expected_rate, upper_bound

    return (f"{k} of {n}; new good parts: about {100 * expected_rate(k, n):.1f} %, at most "
            f"{100 * upper_bound(k, n):.1f} % at 95 % confidence")


def describe_left_out(left_out: Mapping[Any, str], most: int = 10) -> str:
    """``judged_part_of``'s left-out samples in one line (the first ``most``)."""
    text = "; ".join(f"sample {i}: {why}" for i, why in list(left_out.items())[:most])
    return text + (f"; and {len(left_out) - most} more" if len(left_out) > most else "")


def _threshold_and_save(ck, model: str, det, va, val_data: str, out: str, max_good_flagged: float, key: str,
                       record: dict, frame_statistics: dict | None = None):
    """``det`` (a copy of checkpoint ``ck``, loaded from ``model``, with a part added) evaluated on the val split
    ``va`` of ``val_data``, thresholded there with ``station threshold``'s rule and written to ``out``, its sidecar's
    ``train.<key>`` = ``record`` plus the calibration set, its manifest hash and good parts, the date and ``model``;
    ``train.frame_statistics`` (the drift monitor's trained range) = ``frame_statistics`` when given.
    Returns (the threshold choice, the evaluation, the val labels)."""
    from model.draem.checkpoint import save_checkpoint
    from model.draem.metrics import choose_threshold
    from model.normals.estimator import copy_beside
    from station.datasets import manifest_sha256

    train = {**ck.meta.get("train", {}), key: record}
    va = without_held_out_type(va, train)
    _, ev = evaluate_tensors(det, va)
    labels = va.label.numpy()
    choice = choose_threshold(labels, ev.scores, max_good_flagged)
    train[key] = {**record, "calibration_data": str(val_data), "calibration_manifest_sha256": manifest_sha256(val_data),
                  "calibration_parts": int((labels == 0).sum()), "calibration_defective": int(labels.sum()),
                  "date": time.strftime("%Y-%m-%dT%H:%M:%S"), "from": str(model)}
    if frame_statistics is not None:
        train["frame_statistics"] = frame_statistics
    save_checkpoint(out, det, choice.threshold, choice.rule, ck.meta.get("data_manifest_sha256"), ev.metrics, train)
    copy_beside(model, out, train.get("normal_prior"))  # a learned normal prior's estimator goes with it
    return choice, ev, labels


def fit_variation(model: str, data: str, out: str, max_good_flagged: float = GOOD_REJECTED_RATE,
                  val_data: str | None = None,
                  decision: str = "variation", fit_parts: int | None = None,
                  blur_copies_sigma: float | None = None, refit: bool = False,
                  global_polarization: str | None = None, clusters: int | None = None,
                  global_contrast: str | None = None, second_look: bool | None = None,
                  curvature_sigma: float | None = None, second_look_test: bool | None = None,
                  judged_priors: list[str] | None = None, smooth_field: bool | None = None) -> str:
    """Checkpoint ``model`` plus the variation model fitted on ``data``'s good train parts and calibrated on the good
    parts of ``val_data``'s val split (default ``data``'s), thresholded on that split (``set_threshold``'s rule),
    written to ``out``; one line saying what it does on the val split. ``decision``: ``ModelConfig.decision``
    ("variation", the shipped recipe: the variation model's finding alone rejects; "combined": either detector's).
    ``fit_parts``: fit on the first that many good train parts only (None: all of them), to measure how many a line
    needs. ``blur_copies_sigma``: the fit also sees a blurred copy of each good part, blurs up to this many input px
    (0: none; None: ``model.draem.variation.BLUR_COPIES_SIGMA``, the shipped recipe). ``refit``: ``model`` already
    has a variation model; fit it again (its networks kept; otherwise that is an error). ``global_polarization``:
    an ``Alignment`` name, how each frame's polarization is first put onto the good parts' by one
    frame-wide gain and turn (None: the shipped recipe, ``model.draem.variation.shipped_alignment``). ``clusters``:
    how many groups of good parts, by appearance, each part is judged within (0: none; None: the shipped recipe,
    ``model.draem.variation.APPEARANCE_CLUSTERS``; fewer when there are few parts). ``global_contrast``: an
    ``Alignment`` name, how each frame's contrast (log intensity's frame-wide gain) is put onto the good parts' (None:
    the shipped recipe, ``model.draem.variation.GLOBAL_CONTRAST``). ``second_look``: keep the good parts' left-out
    residuals and look again at suspicious parts (``model.draem.second_look``; None: the shipped recipe,
    ``model.draem.variation.SECOND_LOOK``). ``curvature_sigma``: the window statistic, the curvature's sigma in
    input px, 0 for the box (None: the shipped recipe, ``model.draem.variation.CURVATURE_SIGMA``).
    ``second_look_test``: the second look tests where the map points (False: it only gates the parts a look network
    is asked about; None: the shipped recipe, ``model.draem.variation.SECOND_LOOK_TEST``). ``judged_priors``: the
    priors whose channels the window is taken over (None: all, the shipped recipe; the others are read, intensity
    registers the part: ``model.draem.variation``'s ``judged_channels``). ``smooth_field``: take a lens's smooth
    field out of every frame's residual (None: the shipped recipe, ``model.draem.variation.SMOOTH_FIELD``). The
    sidecar's frame statistics (the drift monitor's trained range, ``station.drift``) become those of the parts
    fitted: the variation model decides, and may be fitted on another line than its networks."""
    from model.draem.checkpoint import load_checkpoint
    from model.draem.config import Alignment
    from model.draem.errors import ModelError
    from model.draem.second_look import MIN_REFERENCES
    from model.draem.variation import (
        APPEARANCE_CLUSTERS,
        BLUR_COPIES_SIGMA,
        CURVATURE_SIGMA,
        GLOBAL_CONTRAST,
        MAX_CURVATURE_SIGMA,
        MIN_FIT_PARTS,
        SECOND_LOOK,
        SECOND_LOOK_TEST,
        SMOOTH_FIELD,
        shipped_alignment,
    )
    from model.draem.with_variation import add_variation, judged_channels, without_variation
    from model.priors.frame_stats import StatisticsRange
    from station.datasets import manifest_sha256

    check_max_good_flagged(max_good_flagged)
    blur_copies_sigma = BLUR_COPIES_SIGMA if blur_copies_sigma is None else blur_copies_sigma
    clusters = APPEARANCE_CLUSTERS if clusters is None else clusters
    second_look = SECOND_LOOK if second_look is None else second_look
    curvature_sigma = CURVATURE_SIGMA if curvature_sigma is None else curvature_sigma
    second_look_test = SECOND_LOOK_TEST if second_look_test is None else second_look_test
    smooth_field = SMOOTH_FIELD if smooth_field is None else smooth_field
    if not 0.0 <= curvature_sigma <= MAX_CURVATURE_SIGMA:
        raise UserError(f"--curvature {curvature_sigma}: give the curvature's sigma in input px, in [0, "
                        f"{MAX_CURVATURE_SIGMA:g}] (0: the box window)")
    if clusters < 0:
        raise UserError(f"--clusters {clusters}: give a number of clusters, >= 0 (0: none)")
    try:
        alignment = Alignment.of(global_polarization) if global_polarization is not None else None
    except ModelError as exc:
        raise UserError(f"--global-polarization: {exc}") from None
    try:
        contrast = GLOBAL_CONTRAST if global_contrast is None else Alignment.of(global_contrast, "global_contrast")
    except ModelError as exc:
        raise UserError(f"--global-contrast: {exc}") from None
    if not (math.isfinite(blur_copies_sigma) and blur_copies_sigma >= 0):
        raise UserError(f"--blur-copies {blur_copies_sigma}: give a blur in input px, >= 0 (0: no copies)")
    if fit_parts is not None and fit_parts < MIN_FIT_PARTS:
        raise UserError(f"--fit-parts {fit_parts}: the variation model needs at least {MIN_FIT_PARTS} good parts")
    ck = load_checkpoint(model)
    networks = ck.detector
    if alignment is None:
        alignment = shipped_alignment(networks.config.priors)
    try:  # the model's own refusals first, before minutes of loading
        if networks.config.variation and refit:
            networks = without_variation(networks)
        elif networks.config.variation:
            raise ModelError("the detector already has a variation model (--refit fits it again)")
        networks.config.with_(variation=True, decision=decision)
    except ModelError as exc:
        raise UserError(f"{model}: {exc}") from None
    try:
        judged_channels(networks.config.priors, judged_priors)
    except ModelError as exc:
        raise UserError(f"--judged-priors {','.join(judged_priors or [])}: {model}: {exc}") from None
    tr = model_split(ck, model, data, "train", limit=fit_parts, good_only=True)
    val_data = val_data or data
    va = model_split(ck, model, val_data, "val")
    good_va = va.label == 0
    if len(tr.index) < MIN_FIT_PARTS or int(good_va.sum()) < 2:
        raise UserError(f"{data}, {val_data}: the variation model needs >= {MIN_FIT_PARTS} good train parts and >= 2 "
                        f"good val parts, got {len(tr.index)} and {int(good_va.sum())}")
    try:
        det = add_variation(networks, tr.priors, tr.object_mask if tr.object_masks_known else None,
                            va.priors[good_va], decision=decision, blur_copies_sigma=blur_copies_sigma,
                            global_polarization=alignment, clusters=clusters, global_contrast=contrast,
                            second_look=second_look, curvature_sigma=curvature_sigma,
                            second_look_test=second_look_test, judged_priors=judged_priors,
                            smooth_field=smooth_field)
    except ModelError as exc:
        raise UserError(f"{model}: {exc}") from None
    choice, ev, labels = _threshold_and_save(ck, model, det, va, val_data, out, max_good_flagged, "variation", {
        "data": str(data), "manifest_sha256": manifest_sha256(data), "fit_parts": len(tr.index),
        "blur_copies_sigma": blur_copies_sigma, "global_polarization": alignment.value,
        "clusters": det.variation.clusters, "global_contrast": contrast.value,
        "contrast_range": det.variation.contrast_range.tolist() if det.variation.aligns_contrast else None,
        "second_look_references": det.variation.second_look.references,
        "curvature_sigma": float(det.variation.curvature_sigma),
        "second_look_test": det.variation.second_look.testing if det.variation.second_look.references else None,
        "judged_priors": judged_priors, "smooth_field": det.variation.takes_smooth_field},
        StatisticsRange.from_frames(tr.frame_stats).to_dict())
    n_bad = int(labels.sum())
    detected = f" and {choice.detected_fraction:.1%} of defective" if n_bad else ""
    decides = "" if decision == "combined" else f" (decision: {decision} alone)"
    copies = f" and a blurred copy of each (up to {blur_copies_sigma:g} px)" if blur_copies_sigma else ""
    copies += {Alignment.MEAN: ", each frame's polarization aligned to theirs",
               Alignment.RANGE: ", each frame's polarization aligned where beyond theirs",
               }.get(alignment, "")
    copies += f", judged within {det.variation.clusters} clusters by appearance" if det.variation.clusters else ""
    copies += {Alignment.MEAN: ", each frame's contrast aligned to theirs",
               Alignment.RANGE: ", each frame's contrast aligned where beyond theirs"}.get(contrast, "")
    if curvature_sigma:
        copies += f", its window each channel's curvature over {curvature_sigma:g} px"
    if judged_priors:
        copies += f", judging {', '.join(judged_priors)} only"
    if det.variation.takes_smooth_field:
        copies += ", a lens's smooth field taken out"
    looks = det.variation.second_look.references
    if looks and det.variation.second_look.testing:
        copies += f", a second look at suspicious parts against {looks} of them"
    elif looks:
        copies += ", a second look's gate only (no test: a look network, when added, is asked above it)"
    elif second_look:
        copies += f", no second look (it needs >= {MIN_REFERENCES} good parts)"
    return (f"{out}: variation model fitted on {len(tr.index)} good parts{copies}{decides}; threshold "
            f"{choice.threshold:.4g} ({choice.rule}); on {len(labels)} val parts it flags "
            f"{choice.flagged_good_fraction:.1%} of good parts{detected}; "
            f"image AUROC {ev.metrics.get('image_auroc', float('nan')):.3f}")


def residual_states(out: str, recipe: dict[str, Any]) -> Path:
    """The folder of ``station residual``'s resume states for ``out`` (``OUT.resume``), checked against the
    training's ``recipe`` (what its networks learn from; its ``recipe.json``, written when training starts): a rerun
    of the same training continues from the members' states there; of another, it stops with one line naming the
    folder and what differs (a folder with no member's state is taken over)."""
    folder = Path(f"{out}.resume")
    f = folder / "recipe.json"
    if f.is_file() and any(folder.glob("member-*.pt")):
        try:
            saved = json.loads(f.read_text())
        except (OSError, ValueError) as exc:
            raise UserError(f"{f}: unreadable ({exc}); delete {folder} to train from the start") from None
        if saved != recipe:
            diff = ", ".join(k for k in sorted(set(saved) | set(recipe)) if saved.get(k) != recipe.get(k))
            raise UserError(f"{folder}: the resume states of another training ({diff} differ); delete the folder "
                            f"or give another --out")
    return folder


def fit_residual(model: str, data: str, out: str, val_data: str | None = None, members: int = 3, steps: int = 3000,
                 seed: int = 0, holdout_type: str | None = None, max_good_flagged: float = GOOD_REJECTED_RATE,
                 look: bool = False, more_defects: Sequence[str] = (),
                 lens_copies: tuple[float, float] | None = None) -> str:
    """Checkpoint ``model`` (with its variation model) plus ``members`` residual networks (``model.draem.residual``)
    deciding (``look``: as the variation model's second look instead, the model's decision kept), trained on
    ``data``'s train split (good parts and rendered defective parts with masks, without ``holdout_type``'s; plus the
    defective train parts of each set in ``more_defects``, whose good parts are not used: the good parts' residuals
    are left out of the fit on ``data``'s), calibrated and thresholded on ``val_data``'s val split (default
    ``data``'s) as ``fit_variation``; written to ``out``; one line saying what it does on the val split.
    ``lens_copies``: the vignetting range (share of light lost at the frame's corners) of a lens copy of each good
    part the networks also learn from (``model.draem.lens_copies``), placed by ``data``'s frame; None: none. Progress
    on stderr."""
    import sys

    import torch

    from model.draem.checkpoint import load_checkpoint, paths, sha256_file
    from model.draem.errors import ModelError
    from model.draem.lens_copies import LensCopies
    from model.draem.roi import roi_box
    from model.draem.with_variation import add_residual, can_look
    from sim.defects import DEFECT_TYPES
    from station.datasets import frame_shape_of, manifest_sha256

    check_max_good_flagged(max_good_flagged)
    if holdout_type is not None and holdout_type not in DEFECT_TYPES:
        raise UserError(f"--holdout-type {holdout_type!r}: not a defect type ({', '.join(DEFECT_TYPES)})")
    if members < 1 or steps < 1:
        raise UserError(f"--members {members}, --steps {steps}: both must be >= 1")
    ck = load_checkpoint(model)
    if ck.detector.variation is None:
        raise UserError(f"{model}: the residual networks read the variation model: add it first (station variation)")
    if ck.detector.residual is not None:  # the model's own refusal, before minutes of loading
        raise UserError(f"{model}: the detector already has residual networks: start from the model they were added "
                        f"to ({ck.meta.get('train', {}).get('residual', {}).get('from', 'its train.residual.from')})")
    if look and not can_look(ck.detector):
        raise UserError(f"{model}: --second-look needs a model decided by its variation model with its second look "
                        f"(station variation --decision variation --second-look)")  # before minutes of loading
    for d in more_defects:  # before minutes of loading
        if Path(d).resolve() == Path(data).resolve():
            raise UserError(f"--more-defects {d}: the training set itself (--data); give another rendered set")
    lens = None
    if lens_copies is not None:
        frame = frame_shape_of(data)
        if frame is None:
            raise UserError(f"{Path(data) / 'manifest.json'}: width, height: --lens-copies places the view under the "
                            f"lens by the set's frame size, and the manifest does not give it")
        cfg = ck.detector.config
        try:
            lens = LensCopies(lens_copies, frame, roi_box(cfg.roi, frame, frame_aspect=cfg.frame_aspect), seed)
        except ModelError as exc:
            raise UserError(f"--lens-copies: {exc}") from None
    manifests = {d: manifest_sha256(d) for d in (data, *more_defects)}
    recipe = {"model_sha256": sha256_file(paths(model)[0]), "manifest_sha256": manifests[data],
              "more_defects": [manifests[d] for d in more_defects], "holdout_type": holdout_type, "steps": steps,
              "seed": seed}  # what the networks learn from, whatever the paths it is given by
    lens_record = None if lens is None else lens.to_record()
    if lens_record is not None:  # only then: resume states written before the option stay valid
        recipe["lens_copies"] = lens_record
    states = residual_states(out, recipe)  # before minutes of loading
    tr = model_split(ck, model, data, "train")
    good = [i for i, lab in enumerate(tr.label.tolist()) if not lab]
    defects, masks, learned = [], [], set()
    for root, sp in ((data, tr), *((d, model_split(ck, model, d, "train")) for d in more_defects)):
        keep = [i for i, (lab, t) in enumerate(zip(sp.label.tolist(), sp.defect_type, strict=True))
                if lab and t != holdout_type and sp.mask_known is not None and bool(sp.mask_known[i])]
        if root != data and not keep:
            raise UserError(f"--more-defects {root}: no defective train parts with masks (station render "
                            f"--defects-in-train){f' besides {holdout_type}' if holdout_type else ''}")
        defects.append(sp.priors[keep])
        masks.append(sp.defect_mask[keep].bool())
        learned |= {sp.defect_type[i] for i in keep}
    val_data = val_data or data
    va = model_split(ck, model, val_data, "val")
    good_va = va.label == 0
    n_def = sum(len(d) for d in defects)
    print(f"{data}: {len(good)} good and {n_def} defective train parts"
          f"{f' ({n_def - len(defects[0])} from --more-defects)' if more_defects else ''}"
          f"{f' (without {holdout_type})' if holdout_type else ''}; {members} networks x {steps} steps",
          file=sys.stderr, flush=True)
    record = {"data": str(data), "manifest_sha256": manifests[data], "good_parts": len(good),
              "more_defects": [{"data": str(d), "manifest_sha256": manifests[d]} for d in more_defects],
              "defective_parts": n_def, "holdout_type": holdout_type, "types": sorted(learned), "members": members,
              "steps": steps, "seed": seed, "look": look, "lens_copies": lens_record}
    states.mkdir(parents=True, exist_ok=True)
    (states / "recipe.json").write_text(json.dumps(recipe, indent=1))
    try:
        det = add_residual(ck.detector, tr.priors[good], tr.object_mask[good] if tr.object_masks_known else None,
                           torch.cat(defects), torch.cat(masks), va.priors[good_va], members, steps, seed,
                           progress=lambda line: print(line, file=sys.stderr, flush=True), look=look, states=states,
                           lens=lens)
    except ModelError as exc:
        raise UserError(f"{model}: {exc}") from None
    choice, ev, labels = _threshold_and_save(ck, model, det, va, val_data, out, max_good_flagged, "residual", record)
    shutil.rmtree(states)
    detected = f" and {choice.detected_fraction:.1%} of defective" if int(labels.sum()) else ""
    role = "are the variation model's second look" if look else "decide"
    return (f"{out}: {members} residual networks {role}; threshold {choice.threshold:.4g} ({choice.rule}); on "
            f"{len(labels)} val parts it flags {choice.flagged_good_fraction:.1%} of good parts{detected}; image "
            f"AUROC {ev.metrics.get('image_auroc', float('nan')):.3f}")


def fit_shape(model: str, data: str, val_data: str, out: str) -> str:
    """Checkpoint ``model`` (with its variation model) plus the shape check (``model.draem.shape_check``) and the
    outline check (``model.draem.outline_check``): their medians and spreads from ``data``'s good train parts, their
    thresholds from ``val_data``'s good val parts; written to ``out`` with ``model``'s threshold, its sidecar's
    ``train.shape`` recording the checks (``outline``: None when it is off); one line saying what they found, or why
    the outline check is off. UserError when the model has no variation model or its part shows no straight bottom
    edge."""
    import sys

    from model.draem.checkpoint import load_checkpoint, save_checkpoint
    from model.draem.errors import ModelError
    from model.draem.with_variation import add_outline_check, add_shape_check
    from model.normals.estimator import copy_beside
    from station.datasets import manifest_sha256

    ck = load_checkpoint(model)
    if ck.detector.variation is None:
        raise UserError(f"{model}: the shape check reads the variation model's registration: add it first "
                        f"(station variation)")
    tr = model_split(ck, model, data, "train", good_only=True)
    va = model_split(ck, model, val_data, "val", good_only=True)
    print(f"{data}: {len(tr.priors)} good train parts; {val_data}: {len(va.priors)} good val parts", file=sys.stderr,
          flush=True)
    det = ck.detector  # loaded for this alone: given its check in place
    det.variation.outline.clear()  # a file fitted before: the window's 1 % point is the window's own
    try:
        found = add_shape_check(det, tr.priors, va.priors)
    except ModelError as exc:
        raise UserError(f"{model}: {exc}") from None
    if not found:
        raise UserError(f"{model}: the variation model's part region shows no straight bottom edge along the part: "
                        f"no shape check")
    shape = det.variation.shape
    outline_off = add_outline_check(det, tr.priors, va.priors, window=float(shape.calibration[3]))
    first, end = (int(v) for v in shape.edge[:2])
    centre, spread, threshold, window = (float(v) for v in shape.calibration)
    record = {"data": str(data), "manifest_sha256": manifest_sha256(data), "good_parts": len(tr.priors),
              "calibration_data": str(val_data), "calibration_manifest_sha256": manifest_sha256(val_data),
              "calibration_parts": len(va.priors), "edge_columns": [first, end], "sag_median_px": centre,
              "sag_spread_px": spread, "threshold_z": threshold, "window_at_threshold": window,
              "outline": outline_record(det.variation.outline),
              "date": time.strftime("%Y-%m-%dT%H:%M:%S"), "from": str(model)}
    meta = ck.meta
    save_checkpoint(out, det, ck.threshold, meta.get("threshold_rule", ""), meta.get("data_manifest_sha256"),
                    meta.get("metrics"), {**meta.get("train", {}), "shape": record})
    copy_beside(model, out, meta.get("train", {}).get("normal_prior"))
    return (f"{out}: shape check on the bottom edge over input columns {first}-{end - 1}: good parts' sag "
            f"{centre:.3f} +- {spread:.3f} px; a part is flagged beyond {threshold:.1f} robust SD "
            f"({threshold * spread:.2f} px off), where the largest of {len(va.priors)} good val parts lies; "
            f"{outline_words(det.variation.outline, outline_off)}; threshold {ck.threshold} kept")


def fit_blend(model: str, data: str, out: str, weight: float | None = None,
              max_good_flagged: float = GOOD_REJECTED_RATE) -> str:
    """Checkpoint ``model`` (whose residual networks are its variation model's look) with the look blended
    (``model.draem.residual.blended``): the window's share ``weight`` (None: ``BLEND_WEIGHT``), the two 1 %
    thresholds from ``data``'s good val parts, which then set the threshold with ``station threshold``'s rule;
    written to ``out``, its sidecar's ``train.blend`` recording them; one line saying what it does there."""
    from model.draem.checkpoint import load_checkpoint
    from model.draem.errors import ModelError
    from model.draem.residual import BLEND_WEIGHT
    from model.draem.with_variation import add_blend

    check_max_good_flagged(max_good_flagged)
    weight = BLEND_WEIGHT if weight is None else weight
    if not 0.0 < weight <= 1.0:
        raise UserError(f"--weight {weight}: the window's share of the blend must be in (0, 1]")
    ck = load_checkpoint(model)
    if ck.detector.residual is None or not ck.detector.residual.looks:  # before minutes of loading
        raise UserError(f"{model}: the blend weighs the residual networks' finding as the variation model's second "
                        f"look, and the model has none (station residual --second-look)")
    va = model_split(ck, model, data, "val")
    good = va.label == 0
    try:
        det = add_blend(ck.detector, va.priors[good], weight, None if va.around is None else va.around[good])
    except ModelError as exc:
        raise UserError(f"{model}: {exc}") from None
    assert det.residual is not None
    _, t_w, t_f = (float(v) for v in det.residual.blend)
    record = {"weight": weight, "window_threshold": t_w, "finding_threshold": t_f, "good_parts": int(good.sum())}
    choice, ev, labels = _threshold_and_save(ck, model, det, va, data, out, max_good_flagged, "blend", record)
    detected = f" and {choice.detected_fraction:.1%} of defective" if int(labels.sum()) else ""
    return (f"{out}: the look blended ({weight:g} of the window's finding over its 1 % threshold {t_w:.4g}, "
            f"{1 - weight:g} of the network's over {t_f:.4g}, asked about every part); threshold "
            f"{choice.threshold:.4g} ({choice.rule}); on {len(labels)} val parts it flags "
            f"{choice.flagged_good_fraction:.1%} of good parts{detected}; image AUROC "
            f"{ev.metrics.get('image_auroc', float('nan')):.3f}")


def outline_record(outline: OutlineCheck) -> dict | None:
    """The sidecar's record of a fitted ``model.draem.outline_check.OutlineCheck`` (None when it is off)."""
    if not outline.fitted:
        return None
    first, end = (int(v) for v in outline.edges[0, :2])
    bottom, top, window = (float(v) for v in outline.calibration)
    return {"edge_columns": [first, end], "bottom_row_at_0": float(outline.edges[0, 2]),
            "top_row_at_0": float(outline.edges[1, 2]), "threshold_z": {"bottom": bottom, "top": top},
            "window_at_threshold": window}


def outline_words(outline: OutlineCheck, why_off: str | None) -> str:
    """What ``station shape`` says of the outline check it fitted, or why there is none (``why_off``)."""
    r = outline_record(outline)
    if r is None:
        return f"no outline check ({why_off})"
    first, end = r["edge_columns"]
    z = r["threshold_z"]
    return (f"outline check on the bottom and top edges over input columns {first}-{end - 1}: a step flagged beyond "
            f"{z['bottom']:.1f} and {z['top']:.1f} robust SD")


def split_camera_thresholds(first_model: str, first_data: str | Sequence[str], second_model: str,
                            second_data: str | Sequence[str], rate: float = GOOD_REJECTED_RATE, split: str = "val",
                            first_presence: str = PRESENCE_RULES[0],
                            second_presence: str = PRESENCE_RULES[1], expected: bool = True) -> dict:
    """Two cameras' thresholds from one budget of good parts rejected (``model.draem.camera_split``), on the twin
    validation sets ``first_data`` and ``second_data`` (the same parts, each seen by its camera; their samples are
    matched by index). Several sets pool their parts: ``first_data[j]`` is the twin of ``second_data[j]``, and each
    pair must hold other parts (another seed) than the rest. A part is defective when either camera's sample shows
    its defect (a label says what that camera sees); where both do, the defect types must agree. Parts either
    camera's presence rule (or invalid pixels) would leave unjudged are left out and listed, as ``station threshold``
    does. Returns the report ``station split`` prints and writes: every split of the budget, the chosen one, what
    each camera alone does at the whole budget, and each part's two scores (``part_scores``). ``expected`` (rule
    64): the budget holds ``rate`` for new good parts on average (``camera_split.expected_budget``); False: as a
    count on these (floor(rate x good parts))."""
    import dataclasses

    import numpy as np

    from model.draem.camera_split import count_budget, expected_budget, split_thresholds
    from model.draem.checkpoint import load_checkpoint
    from model.draem.metrics import choose_threshold

    check_max_good_flagged(rate)
    firsts, seconds = _twin_sets(first_data, second_data)
    scores, labels, types, left_out = [{}, {}], [{}, {}], [{}, {}], {}
    for c, (name, model, sets, rule) in enumerate((("first", first_model, firsts, first_presence),
                                                   ("second", second_model, seconds, second_presence))):
        ck = load_checkpoint(model)
        net = inference_net(ck, model, "fp32")
        for j, (data, (sp, unjudged)) in enumerate(zip(sets, _judged_splits(ck, model, sets, split, rule),
                                                        strict=True)):
            _, ev = evaluate_tensors(net, sp)
            keys = [(j, i) for i in sp.index]
            scores[c].update(zip(keys, np.asarray(ev.scores, np.float64).tolist(), strict=True))
            labels[c].update(zip(keys, sp.label.numpy().astype(int).tolist(), strict=True))
            types[c].update(zip(keys, sp.defect_type, strict=True))
            where = f" of {data}" if len(sets) > 1 else ""
            left_out.update({(j, i): f"{name} camera{where}: {why}" for i, why in unjudged.items()})
    both = sorted(set(scores[0]) & set(scores[1]))
    wrong = [k for k in both if labels[0][k] and labels[1][k] and types[0][k] != types[1][k]]
    if wrong:
        j, i = wrong[0]
        raise UserError(f"{firsts[j]} and {seconds[j]} are not twin sets: sample {i} shows a {types[0][(j, i)]} in "
                        f"one and a {types[1][(j, i)]} in the other ({len(wrong)} such)")
    if not both:
        raise UserError(f"{', '.join(firsts)} and {', '.join(seconds)}: no sample of split {split!r} is judged by "
                        "both cameras")
    y = np.array([labels[0][i] or labels[1][i] for i in both], bool)
    a = np.array([scores[0][i] for i in both])
    b = np.array([scores[1][i] for i in both])
    try:
        budget = (expected_budget if expected else count_budget)(int((~y).sum()), rate)
        rows, best = split_thresholds(y, a, b, rate, budget)
    except ValueError as exc:
        raise UserError(f"{', '.join(firsts)}, {', '.join(seconds)}: {exc}") from None
    chosen = rows[best]
    above = {"first": int((a[~y] > chosen.first).sum()), "second": int((b[~y] > chosen.second).sum())}
    alone = {}
    for name, s in (("first", a), ("second", b)):
        choice = choose_threshold(y.astype(int), s, rate)
        alone[name] = {"threshold": choice.threshold, "good_rejected": choice.flagged_good_fraction,
                       "caught": choice.detected_fraction}
    one = len(firsts) == 1
    part_scores = [{"set": j, "index": int(i), "defective": bool(d),
                    "defect_type": types[0][(j, i)] or types[1][(j, i)], "first": s1, "second": s2}
                   for (j, i), d, s1, s2 in zip(both, y, a, b, strict=True)]
    return {"first": {"model": first_model, "data": firsts[0] if one else firsts, "presence_rule": first_presence},
            "second": {"model": second_model, "data": seconds[0] if one else seconds,
                       "presence_rule": second_presence},
            "split": split, "rate": rate, "parts": len(both), "good": int((~y).sum()), "defective": int(y.sum()),
            "budget": budget, "expected": expected,
            "left_out": {_sample_key(j, i, not one): why for (j, i), why in sorted(left_out.items())},
            "splits": [dataclasses.asdict(r) for r in rows], "chosen": best, "chosen_good_above": above,
            "alone": alone, "part_scores": part_scores}


def _twin_sets(first: str | Sequence[str], second: str | Sequence[str]) -> tuple[list[str], list[str]]:
    """The twin validation sets of ``split_camera_thresholds`` as two lists of paths, one pair per index
    (``_set_list`` each)."""
    firsts, seconds = _set_list(first, "--data"), _set_list(second, "--second-data")
    if len(firsts) != len(seconds):
        raise UserError(f"--data names {len(firsts)} sets and --second-data {len(seconds)}: each first camera's set "
                        "needs its twin, in the same order")
    return firsts, seconds
