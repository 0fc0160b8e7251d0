"""``station eval``: evaluate a trained detector on a rendered dataset's test split.

Reports image AUROC, pixel AUROC, AUPRO (FPR <= 0.3), pixel AP, image F1-max and the checkpoint's threshold's
effect, separately on rendered physical defects (all, and per defect type against all good parts) and on
DRAEM-style synthetic anomalies on the good test parts; on sets rendered with ``--visibility``, caught share and image
AUROC per detectability bin (``station.detectability``). Writes JSON + Markdown, ROC curves and example heatmaps on
a fixed [0, 1] scale (never per-image min-max, which makes good parts look bad). In the industrial figures (caught
at a fixed share of good parts rejected), a frame the station would not judge (no part in view for the camera's
presence rule, ``--presence-rule``; too many invalid pixels) counts as rejected, as a triggered station rejects it;
the validation thresholds leave such frames out, as ``station threshold`` does.
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path
from typing import TYPE_CHECKING

from model.draem.holdout import held_out_type, learned_types, learning_record
from model.draem.runtime import EVAL_PRECISIONS
from sim.defects import DEFECT_TYPES
from station.commands.arguments import add_presence_rule, positive_int
from station.errors import UserError
from station.evaluation import ABLATION, describe_left_out, evaluate_split, load_and_evaluate, normal_prior_record

if TYPE_CHECKING:
    import numpy as np


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("eval", help="evaluate a trained detector (AUROC, AUPRO, AP, F1, per defect type, plots)")
    p.add_argument("--model", required=True,
                   help="checkpoint path without suffix (e.g. runs/train/fast-ensemble/best); "
                   "with --ablation also several fused checkpoints, comma-separated, one per prior set")
    p.add_argument("--data", required=True, help="dataset folder (rendered, or imported by station import)")
    p.add_argument("--split", default="test", choices=("train", "val", "test"))
    p.add_argument("--limit", type=positive_int, default=None, help="at most N samples (smoke runs)")
    p.add_argument("--no-synthetic", action="store_true", help="skip the synthetic-anomaly evaluation")
    p.add_argument("--ablation", action="store_true",
                   help="the paper's ablation (R, R+AoLP, R+AoLP+DoLP, all): an ensemble's members averaged, or "
                        "several fused models (--model A,B,...) side by side")
    p.add_argument("--precision", default="fp32", choices=EVAL_PRECISIONS,
                   help="int8: the model's int8 networks from `station quantize` (ONNX Runtime, CPU)")
    p.add_argument("--val-data", default=None, metavar="DATA",
                   help="set whose val split fixes the industrial thresholds (default: --data; a held-out set, "
                        "rendered with --heldout, has none: give a validation set, rendered with --validation, or "
                        "the set the model was trained and selected on; with --split val, another set: e.g. a "
                        "validation set of other kinds scored against the line's thresholds)")
    p.add_argument("--no-plots", action="store_true")
    p.add_argument("--out", default=None, help="report folder (default: <model folder>/eval-<split>)")
    add_presence_rule(p)
    p.set_defaults(func=run)


def pixel_metrics_scope(n_anomalous: int, n_with_mask: int) -> str:
    """What the pixel metrics cover when defective parts lack masks (imported sets); "" when all have one."""
    if n_with_mask == n_anomalous:
        return ""
    if n_with_mask == 0:
        return (f"No defect masks in this split ({n_anomalous} defective parts): image-level metrics only; the pixel "
                f"metrics (NaN) are not computed against all-zero masks.")
    return (f"Pixel metrics on the {n_with_mask} of {n_anomalous} defective parts that have a mask (and all good "
            f"parts); image metrics on all.")


def _rows(name: str, m: dict, threshold: float | None, scores, labels, rejected=None) -> dict:
    """One row of the first table; ``flagged_good`` and ``detected`` at ``threshold`` count the parts ``rejected``
    whatever their score (frames the station would not judge) as flagged."""
    import numpy as np

    row = {"set": name, "n": m["n"], "anomalous": m["n_anomalous"],
           "with_mask": m.get("n_anomalous_with_mask", m["n_anomalous"])}
    for k in ("image_auroc", "pixel_auroc", "aupro_0.3", "pixel_ap", "image_f1_max"):
        row[k] = m[k]
    if threshold is not None:
        y = np.asarray(labels, bool)
        flagged = (np.asarray(scores) > threshold) | (False if rejected is None else np.asarray(rejected, bool))
        row["flagged_good"] = float(flagged[~y].mean()) if (~y).any() else math.nan
        row["detected"] = float(flagged[y].mean()) if y.any() else math.nan
    return row




def ablation_rows(ev, data) -> list[dict]:
    """The paper's ablation from one ensemble: each prefix of ``ABLATION`` whose members the model has, scored by
    averaging those members' maps and image scores (the paper's fusion rule)."""
    import numpy as np

    from model.draem import metrics as M

    label = data.label.numpy().astype(bool)
    known = np.ones(label.size, bool) if data.mask_known is None else data.mask_known.numpy().astype(bool)
    gt, obj = data.defect_mask.numpy().astype(bool)[known], data.object_mask.numpy().astype(bool)[known]
    rows = []
    for name, members in ABLATION:
        if not all(m in ev.member_scores for m in members):
            continue
        score = np.mean([ev.member_scores[m] for m in members], axis=0)
        amap = np.mean([ev.member_maps[m] for m in members], axis=0)[known]
        rows.append({"priors": name, "members": "+".join(members), "image_auroc": M.auroc(label, score),
                     "pixel_auroc": M.pixel_auroc(gt, amap, obj), "pixel_ap": M.pixel_ap(gt, amap, obj)})
    return rows


EARLY_EXIT_MARGINS = (None, 0.0, 0.05, 0.1, 0.2)
"""Rules compared by ``early_exit_rows``: None runs every member, 0 is the exact rule, m > 0 the margin rule."""


def channel_rows(detector, x, object_mask) -> list[dict]:
    """``model.draem.channel_stats`` per input channel, as report rows."""
    from dataclasses import asdict

    from model.draem.channel_stats import channel_stats

    return [asdict(c) for c in channel_stats(detector, x, object_mask)]


def early_exit_rows(ev, label, threshold: float, members: tuple[str, ...]) -> list[dict]:
    """What early exit of the ensemble (``model.draem.early_exit``, members run in ``members`` order) costs on
    these parts: members run per part, decisions that differ from running all members, image AUROC."""
    import numpy as np

    from model.draem import metrics as M
    from model.draem.early_exit import simulate

    scores = np.stack([ev.member_scores[m] for m in members], 1)
    full = scores.mean(1) > threshold
    rows = []
    for margin in EARLY_EXIT_MARGINS:
        s, used = (scores.mean(1), np.full(len(scores), len(members))) if margin is None else \
            simulate(scores, threshold, margin)
        rows.append({"early_exit": "off" if margin is None else "exact" if margin == 0 else f"margin {margin}",
                     "members_per_part": float(used.mean()), "decisions_changed": int(((s > threshold) != full).sum()),
                     "image_auroc": M.auroc(np.asarray(label, bool), s)})
    return rows


FALSE_REJECTS = (0.01, 0.05)
"""The industrial pair's fixed shares of good parts rejected."""


def write_scores(path: Path, sp, ev, separable: list[bool | None] | None = None,
                 faces: list[str | None] | None = None) -> None:
    """One row per part of the evaluated split: its dataset index, label, defect type ("" for good parts), the
    model's decision score, and each member's image score (``ev.member_scores``, e.g. "variation"), so two models
    on the same parts can be compared part by part (a paired bootstrap) and any row audited; with ``separable``
    (``station.told_where``), whether the localised oracle separates each defect (1 / 0, "" for good parts); with
    ``faces`` (a rendered set), the face each defect lies on (``sim.defects.defect_face``; "" when unknown)."""
    import csv

    members = sorted(ev.member_scores)
    extra = ([] if separable is None else ["separable"]) + ([] if faces is None else ["face"])
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["index", "label", "defect_type", "score", *members, *extra])
        for k, (i, y, t) in enumerate(zip(sp.index, sp.label.tolist(), sp.defect_type, strict=True)):
            flag = [] if separable is None else ["" if separable[k] is None else int(separable[k])]
            face = [] if faces is None else [faces[k] or ""]
            w.writerow([i, y, t, f"{float(ev.scores[k]):.6g}", *(f"{float(ev.member_scores[m][k]):.6g}"
                                                                for m in members), *flag, *face])


def detector_rows(ev, label, types: list[str]) -> list[dict]:
    """Image AUROC of a model with the variation member, all defects and per type: the networks alone, the
    variation model alone, the residual networks alone when the model has them, and the model's decision score
    ("combined"). ``label``: (N,) numpy 0/1."""
    import numpy as np
    import torch

    from model.draem import metrics as M
    from model.draem.variation import network_score

    scores = {"networks": network_score({k: torch.from_numpy(v) for k, v in ev.member_scores.items()}).numpy(),
              "variation": ev.member_scores["variation"],
              **({"residual": ev.member_scores["residual"]} if "residual" in ev.member_scores else {}),
              "combined": ev.scores}
    t = np.asarray(types)
    rows = []
    for name in ["all", *sorted(set(types) - {""})]:
        keep = np.ones(len(t), bool) if name == "all" else (label == 0) | (t == name)
        rows.append({"type": name, "parts": int(label[keep].sum()),
                     **{k: M.auroc(label[keep], v[keep]) for k, v in scores.items()}})
    return rows


def industrial_rows(report, train_meta: dict) -> list[dict]:
    """``model.draem.metrics.detection_by_type``'s report as table rows: per defect type (and all), parts, image
    AUROC and the share caught at each of ``FALSE_REJECTS``, and whether the type was among the model's rendered
    training defects ("trained on"), left out of them ("held out"), a kind its training sets never drew ("never in
    training": ``learned_types``; a record without them drew from ``sim.defects.DEFECT_TYPES``) or the model saw
    none ("synthetic only")."""
    # the residual networks, where there are any, learned from rendered defects whatever the networks did
    learned = bool(learning_record(train_meta))
    held = held_out_type(train_meta)
    drawn = learned_types(train_meta)
    drawn = DEFECT_TYPES if drawn is None else drawn
    rows = []
    for det in [report.overall, *report.per_type.values()]:
        seen = ("" if det.defect_type == "all" else "synthetic only" if not learned
                else "held out" if det.defect_type == held
                else "trained on" if det.defect_type in drawn else "never in training")
        rows.append({"type": det.defect_type, "parts": det.n_defective, "in_training": seen,
                     "image_auroc": det.image_auroc,
                     **{f"caught_at_{100 * fr:g}%_false_rejects": det.caught[fr] for fr in FALSE_REJECTS}})
    return rows


def rate_note(rate: float, threshold: float, val_good: np.ndarray, k: int, n_good: int) -> str:
    """One false-reject rate's threshold in the report: how many good validation parts lie above it and what that
    says of new good parts, then the ``k`` of this set's ``n_good`` good parts it rejected, with the share's exact
    95 % interval (``model.draem.rate_bounds``)."""
    from model.draem.rate_bounds import interval
    from station.evaluation import new_good_rate

    low, high = interval(k, n_good) if n_good else (math.nan, math.nan)
    observed = 100 * k / n_good if n_good else math.nan
    return (f"{100 * rate:g} % -> {threshold:.4g} ({new_good_rate(int((val_good > threshold).sum()), len(val_good))}), "
            f"observed here {observed:.1f} % ({k} of {n_good}: 95 % interval {100 * low:.1f}-{100 * high:.1f} %)")


def unjudged_note(unjudged: dict[int, str], sp, rule: str) -> str:
    """The industrial note's clause on the evaluated frames the station would not judge ("" when none): rejected
    whatever their score, as a triggered station rejects an announced part it cannot judge."""
    if not unjudged:
        return ""
    labels = dict(zip(sp.index, sp.label.tolist(), strict=True))
    bad = sum(labels[i] for i in unjudged)
    return (f"; {len(unjudged)} evaluated frames the station would not judge ({len(unjudged) - bad} good, {bad} "
            f"defective; presence rule {rule}) count as rejected: {describe_left_out(unjudged, 5)}")


def prior_set_name(priors: tuple[str, ...]) -> str:
    """The ablation's name for a set of priors ("R+AoLP", ...), or the priors joined by "+" outside it."""
    return next((name for name, members in ABLATION if set(members) == set(priors)), "+".join(priors))


def _ablation_plot(out: Path, rows: list[dict], fusion: str = "ensemble") -> str:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    fig, ax = plt.subplots(figsize=(5, 3.2))
    x = np.arange(len(rows))
    for k, (key, lab) in enumerate((("image_auroc", "image AUROC"), ("pixel_auroc", "pixel AUROC"))):
        ax.bar(x + (k - 0.5) * 0.38, [r[key] for r in rows], 0.38, label=lab)
    ax.set_xticks(x, [r["priors"] for r in rows])
    ax.set(ylim=(0.4, 1.0), ylabel="AUROC", title="ablation: priors averaged in the ensemble" if fusion == "ensemble"
           else "ablation: one fused model per prior set")
    ax.legend(fontsize=7)
    fig.savefig(out / "ablation.png", dpi=120, bbox_inches="tight")
    plt.close(fig)
    return "ablation.png"


def _plots(out: Path, results: dict, data, maps, scores, threshold) -> list[str]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from sklearn.metrics import roc_curve

    files = []
    fig, ax = plt.subplots(figsize=(5, 5))
    for name, (y, s) in results.items():
        if 0 < int(np.sum(y)) < len(y):
            fpr, tpr, _ = roc_curve(y, s)
            ax.plot(fpr, tpr, label=name)
    ax.plot([0, 1], [0, 1], "k:", lw=0.8)
    ax.set(xlabel="false positive rate (good parts flagged)", ylabel="true positive rate", title="image ROC")
    ax.legend(fontsize=7)
    fig.savefig(out / "roc.png", dpi=120, bbox_inches="tight")
    plt.close(fig)
    files.append("roc.png")
    label = data.label.numpy().astype(bool)
    pick = [*np.flatnonzero(~label)[:3], *np.flatnonzero(label)[:5]]
    if pick:
        fig, axes = plt.subplots(2, len(pick), figsize=(2 * len(pick), 4.2), squeeze=False)
        for j, i in enumerate(pick):
            axes[0, j].imshow(data.priors[i, 0].numpy(), cmap="gray")
            axes[0, j].contour(data.defect_mask[i].numpy(), levels=[0.5], colors="r", linewidths=0.6)
            axes[0, j].set_title(f"{'defect' if label[i] else 'good'} s={scores[i]:.2f}", fontsize=7)
            im = axes[1, j].imshow(maps[i], cmap="inferno", vmin=0.0, vmax=1.0)  # fixed scale, not min-max
            for a in axes[:, j]:
                a.axis("off")
        fig.colorbar(im, ax=axes[1, :].tolist(), shrink=0.8, label="anomaly probability")
        fig.suptitle(f"first channel and anomaly map (fixed 0..1 scale); threshold {threshold:.3g}" if threshold
                     is not None else "first channel and anomaly map (fixed 0..1 scale)", fontsize=8)
        fig.savefig(out / "heatmaps.png", dpi=120, bbox_inches="tight")
        plt.close(fig)
        files.append("heatmaps.png")
    return files


def fused_ablation(args: argparse.Namespace, models: list[str]) -> int:
    """The ablation over one fused model per prior set: each evaluated on the same split, rows in the paper's
    order (rendered defects only)."""
    from model.draem.checkpoint import read_sidecar
    from station.benchmarks.report import markdown_table, write_report

    order = [name for name, _ in ABLATION]
    rows = []
    for m in models:
        cfg = read_sidecar(m)["model"]
        if cfg.get("fusion") != "fused":
            raise UserError(f"{m}: --ablation over several models takes fused models; this one is {cfg.get('fusion')}"
                            f" (an ensemble's ablation: --ablation --model <ensemble>)")
        ck, _, _, _, ev = load_and_evaluate(m, args.data, args.split, args.limit, args.precision)
        priors = ck.detector.config.priors
        rows.append({"priors": prior_set_name(priors), "members": "+".join(priors), "model": m,
                     "image_auroc": ev.metrics["image_auroc"], "pixel_auroc": ev.metrics["pixel_auroc"],
                     "pixel_ap": ev.metrics["pixel_ap"], "n": ev.metrics["n"],
                     "anomalous": ev.metrics["n_anomalous"]})
    rows.sort(key=lambda r: order.index(r["priors"]) if r["priors"] in order else len(order))
    out = Path(args.out or Path(models[0]).parent / f"ablation-fused-{args.split}")
    out.mkdir(parents=True, exist_ok=True)
    files = [] if args.no_plots else [_ablation_plot(out, rows, "fused")]
    table = (f"Ablation, one fused model per prior set ({args.data}, split {args.split}, rendered defects):\n\n"
             + markdown_table(rows, ["priors", "model", "n", "anomalous", "image_auroc", "pixel_auroc", "pixel_ap"]))
    write_report(out, "eval", {"data": str(args.data), "split": args.split, "ablation": rows, "plots": files}, table)
    print(table)
    print(f"report: {out / 'eval.json'}, {out / 'eval.md'}" + (f", plots: {', '.join(files)}" if files else ""))
    return 0


def run(args: argparse.Namespace) -> int:
    import numpy as np

    from model.draem.checkpoint import read_sidecar
    from model.draem.evaluate import evaluate, synthetic_eval_data
    from model.draem.metrics import detection_by_type, summary
    from model.draem.train import TensorData
    from sim.dataset import defect_records, open_dataset
    from sim.defects import defect_face
    from station.benchmarks.report import markdown_table, write_report
    from station.datasets import manifest_sha256
    from station.defect_face import COLUMNS as FACE_COLUMNS
    from station.defect_face import by_face as detection_by_face
    from station.defect_face import plot as face_plot
    from station.defect_size import COLUMNS as SIZE_COLUMNS
    from station.defect_size import by_size as detection_by_sizes
    from station.defect_size import plot as size_plot
    from station.detectability import COLUMNS as DETECTABILITY_COLUMNS
    from station.detectability import detection_by_detectability, oracle_snr
    from station.told_where import COLUMNS as TOLD_WHERE_COLUMNS
    from station.told_where import FALSE_REJECT as TOLD_WHERE_FALSE_REJECT
    from station.told_where import plot as told_where_plot
    from station.told_where import told_where

    models = args.model.split(",")
    if len(models) > 1 and not args.ablation:
        raise UserError(f"--model {args.model}: several models only with --ablation (one fused model per prior set)")
    if args.ablation and len(models) > 1:
        return fused_ablation(args, models)
    cfg0 = read_sidecar(args.model)["model"]
    if args.ablation and (cfg0.get("fusion") != "ensemble" or "intensity" not in cfg0.get("priors", ())):
        raise UserError(f"{args.model}: --ablation averages the members of a per-prior ensemble that includes "
                        f"intensity; this model is {cfg0.get('fusion')} over {list(cfg0.get('priors', ()))} (for "
                        f"fused models, train one per prior set and pass them all: --model A,B,...)")
    out = Path(args.out or Path(args.model).parent / f"eval-{args.split}")
    out.mkdir(parents=True, exist_ok=True)
    from station.presence import PresenceCheck

    presence = PresenceCheck(rule=args.presence_rule)
    ck, net, sp, data, ev = load_and_evaluate(args.model, args.data, args.split, args.limit, args.precision,
                                              presence)
    unjudged = {i: why for i, why in zip(sp.index, sp.unjudged, strict=True) if why is not None}
    not_judged = np.array([why is not None for why in sp.unjudged], bool)
    cfg, thr = ck.detector.config, ck.threshold
    evaluated = open_dataset(args.data)
    source = "imported" if evaluated.manifest.get("source") else "rendered"
    rows = [_rows(f"{source}, all defects", ev.metrics, thr, ev.scores, sp.label.numpy(), not_judged)]
    roc = {"rendered": (sp.label.numpy(), ev.scores)}
    good = sp.label == 0
    for t in sorted({t for t in sp.defect_type if t}):
        sel = np.array([(lab == 0) or (dt == t) for lab, dt in zip(sp.label.tolist(), sp.defect_type, strict=True)])
        label = sp.label.numpy()[sel]  # the full pass's scores and maps: the network runs once per part
        m = summary(label, ev.scores[sel], ev.maps[sel], sp.defect_mask.numpy()[sel], sp.object_mask.numpy()[sel],
                    sp.mask_known.numpy()[sel])
        rows.append(_rows(f"{source}, {t}", m, thr, ev.scores[sel], label, not_judged[sel]))
        roc[t] = (label, ev.scores[sel])
    if not args.no_synthetic and bool(good.any()):
        syn = synthetic_eval_data(TensorData(sp.priors[good], sp.object_mask[good]), cfg.priors, seed=4242)
        m = evaluate(net, syn)
        rows.append(_rows("synthetic (DRAEM-style)", m.metrics, thr, m.scores, syn.label.numpy()))
        roc["synthetic"] = (syn.label.numpy(), m.scores)
    if not rows[0]["anomalous"]:
        raise UserError(f"{args.data}: split {args.split!r} has no defective parts; AUROC is undefined")
    files = [] if args.no_plots else _plots(out, roc, data, ev.maps, ev.scores, thr)
    ablation = ablation_rows(ev, data) if args.ablation else []
    channels = channel_rows(ck.detector, sp.priors[good], sp.object_mask[good]) if bool(good.any()) else []
    early = (early_exit_rows(ev, sp.label.numpy(), thr, tuple(cfg.networks()))
             if len(cfg.networks()) > 1 and not cfg.variation and thr is not None else [])
    detectors = detector_rows(ev, sp.label.numpy(), sp.defect_type) if cfg.variation else []
    if ablation and not args.no_plots:
        files.append(_ablation_plot(out, ablation))
    records = defect_records(args.data, sp.index)  # read once, for the tables and scores.csv's faces
    by_snr = detection_by_detectability(sp.label.numpy(), ev.scores, thr, oracle_snr(records), sp.defect_type)
    by_size = (detection_by_sizes(records, sp.label.numpy(), ev.scores, thr, sp.defect_type)
               if source == "rendered" else [])
    if by_size and not args.no_plots:
        files.append(size_plot(out, by_size))
    faces = ([defect_face(r) if int(lab) else None for r, lab in zip(records, sp.label.tolist(), strict=True)]
             if source == "rendered" else None)  # for the table and scores.csv
    by_face = detection_by_face(faces, sp.label.numpy(), ev.scores, thr, sp.defect_type) if faces else []
    if by_face and not args.no_plots:
        files.append(face_plot(out, by_face))
    industrial, industrial_note, rep = [], "", None
    other_val = bool(args.val_data) and Path(args.val_data).resolve() != Path(args.data).resolve()
    if args.split != "val" or other_val:  # thresholds from a val split's good parts, held fixed on this split
        val_data = args.val_data or args.data
        try:
            if not args.val_data and not evaluated.indices("val"):
                raise ValueError(f"{args.data} has no val split (a held-out set): give the set the model was "
                                 f"selected on with --val-data")
            vsp, _, vev = evaluate_split(ck, net, args.model, val_data, "val", args.limit, presence)
            judged = np.array([why is None for why in vsp.unjudged], bool)  # as `station threshold` sets it
            rep = detection_by_type(sp.label.numpy(), ev.scores, sp.defect_type, FALSE_REJECTS,
                                    validation=(vsp.label.numpy()[judged], vev.scores[judged]),
                                    rejected=not_judged)
        except ValueError as exc:
            industrial_note = f"no industrial figures: {exc}"
        else:
            industrial = industrial_rows(rep, ck.meta.get("train") or {})
            val_good = vev.scores[judged][vsp.label.numpy()[judged] == 0]
            industrial_note = ("Defective parts caught at a fixed share of good parts rejected (thresholds set on the "
                               "val split's good parts and held fixed: " + ", ".join(
                                   rate_note(fr, t, val_good, rep.good_rejected[fr], rep.n_good)
                                   for fr, t in rep.thresholds.items())
                               + f"; val split of {val_data}, {len(val_good)} good parts"
                               + unjudged_note(unjudged, sp, args.presence_rule) + "):")
    where, separable = told_where(
        ck.detector.variation, sp.priors, sp.label.numpy(), sp.defect_mask, sp.mask_known.numpy(), sp.defect_type,
        ev.scores, rep.thresholds.get(TOLD_WHERE_FALSE_REJECT) if rep else None
    ) if ck.detector.variation is not None else ([], None)
    if where and not args.no_plots:
        files.append(told_where_plot(out, where))
    write_scores(out / "scores.csv", sp, ev, separable if where else None, faces)
    manifest_ok = ck.meta.get("data_manifest_sha256")
    payload = {"scores": "scores.csv", "model": str(args.model), "precision": args.precision,
               "model_config": cfg.to_dict(), "threshold": thr,
               "threshold_rule": ck.meta.get("threshold_rule"), "data": str(args.data), "split": args.split,
               "same_dataset_as_training": manifest_ok == manifest_sha256(args.data),
               "normal_prior": normal_prior_record(ck), "rows": rows,
               "ablation": ablation, "early_exit": early, "detectors": detectors, "channels": channels,
               "by_detectability": by_snr, "by_size": by_size, "by_face": by_face,
               "told_where": where,
               "industrial": industrial, "industrial_note": industrial_note,
               "industrial_val_data": str(args.val_data or args.data), "presence_rule": args.presence_rule,
               "unjudged": {str(i): why for i, why in unjudged.items()}, "plots": files}
    cols = ["set", "n", "anomalous", "with_mask", "image_auroc", "pixel_auroc", "aupro_0.3", "pixel_ap",
            "image_f1_max", "flagged_good", "detected"]
    table = markdown_table(rows, cols)
    masks = pixel_metrics_scope(int(ev.metrics["n_anomalous"]), int(ev.metrics["n_anomalous_with_mask"]))
    if masks:
        table = masks + "\n\n" + table
    payload["pixel_metrics_scope"] = masks or "all defective parts have masks"
    if industrial_note:
        table += "\n\n" + industrial_note
    if industrial:
        table += "\n\n" + markdown_table(industrial, list(industrial[0]))
    if by_snr:
        table += ("\n\nDetection by detectability (the oracle's best-prior SNR, station/detectability.py; caught: "
                  "score > threshold, the station's rule; image AUROC: these defects against all good parts):\n\n"
                  + markdown_table(by_snr, DETECTABILITY_COLUMNS))
    if by_size:
        table += ("\n\nDetection by defect size (each type's defects in thirds by a size, station/defect_size.py: "
                  "the one that governs the type's visibility, a dent's or blister's steepest tilt, a scratch's "
                  "area, a stain's or particle's radius, a chip's cut; and visible_px, its pixels in the frame; "
                  "caught: score > threshold, the station's rule; image AUROC: these defects against all good "
                  "parts):\n\n"
                  + markdown_table(by_size, SIZE_COLUMNS))
    if by_face:
        table += ("\n\nDetection by the face the defect lies on (station/defect_face.py, in the part's frame: top; "
                  "front, toward the cameras; back; end; bottom; edge, a chip's cut; caught: score > threshold, "
                  "the station's rule; image AUROC: these defects against all good parts):\n\n"
                  + markdown_table(by_face, FACE_COLUMNS))
    if where:
        table += (f"\n\nTold where to look (station/told_where.py): the share of each type's defects whose "
                  f"residual at their own pixels lies above {100 * TOLD_WHERE_FALSE_REJECT:g} % of this split's good "
                  f"parts at the same pixels (the localised oracle, by either statistic: what the features show), "
                  f"the share the model caught at its validation threshold for the same share of good parts, and "
                  f"the image AUROC of the defects the features separate against all good parts:\n\n"
                  + markdown_table(where, TOLD_WHERE_COLUMNS))
    if detectors:
        table += ("\n\nImage AUROC by detector (networks: their mean score; variation: the registered variation "
                  "model, which never saw a defect of any type; residual: the residual networks on its residuals; "
                  "combined: the model's decision score):\n\n" + markdown_table(detectors, list(detectors[0])))
    if ablation:
        table += "\n\nAblation (ensemble members averaged, rendered defects):\n\n" + markdown_table(
            ablation, ["priors", "members", "image_auroc", "pixel_auroc", "pixel_ap"])
    if channels:
        table += ("\n\nInput channels on good parts' object pixels (normalised; unexplained = reconstruction residual "
                  "/ variance; adjacent_corr near 0 = pixel noise):\n\n"
                  + markdown_table(channels, ["channel", "variance", "unexplained", "adjacent_corr"]))
    if early:
        table += (f"\n\nEarly exit of the ensemble (members in order {', '.join(cfg.networks())}; threshold "
                  f"{thr:.4g}; rendered defects):\n\n" + markdown_table(
                      early, ["early_exit", "members_per_part", "decisions_changed", "image_auroc"]))
    write_report(out, "eval", json.loads(json.dumps(payload, default=float)), table)
    print(table)
    print(f"report: {out / 'eval.json'}, {out / 'eval.md'}" + (f", plots: {', '.join(files)}" if files else ""))
    return 0
