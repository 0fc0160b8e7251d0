"""Accuracy when the frames differ from the renders: a model on a held-out set whose priors are changed as another
renderer, lens or camera would change them, with its validation thresholds held fixed (a line that has not adapted).

The shifts are pure functions on the stacked priors at the model's input (``model.draem.shifts``). Per shift:
image AUROC, the share of defective parts caught and of good parts rejected at the thresholds that reject 1 % and 5 %
of the good validation parts, the share rejected at the model's own threshold, and image AUROC per defect type. The
unchanged row is what ``station eval`` reports on the same parts; the frame around the view the variation model's
registration reads (``model.draem.roi.AROUND_PX``) is shifted with it. What it does not cover: noise (a noisier frame is
judged against its own noise level: ``model.draem.variation``, docs/results/2026-11-24-noise-level.md) and a line
whose geometry or light differs (render it: docs/results/2026-11-25-gradient-dome.md)."""

from __future__ import annotations

import argparse
import math

import numpy as np

from model.draem.shifts import SHIFTS, Channels, parse, shift


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--model", default="model/weights/default", help="checkpoint, path without suffix")
    p.add_argument("--data", required=True, help="held-out set (its test split)")
    p.add_argument("--val-data", required=True, metavar="DATA",
                   help="set whose val split's good parts set the 1 %% and 5 %% thresholds, unshifted")
    p.add_argument("--shifts", default=",".join(SHIFTS), help="comma-separated shift names")
    p.add_argument("--limit", type=int, default=None, help="at most N held-out parts (default all)")


def run(args: argparse.Namespace) -> int:
    import torch

    from model.draem.evaluate import EvalData, evaluate
    from model.draem.metrics import auroc, detection_by_type
    from station.benchmarks.report import markdown_table, write_report
    from station.errors import UserError
    from station.evaluation import evaluate_split, inference_net, model_split

    names = [s.strip() for s in args.shifts.split(",") if s.strip()]
    if not names:
        raise UserError(f"--shifts: none given; e.g. {', '.join(SHIFTS)}")
    for name in names:
        try:
            parse(name)
        except ValueError as exc:
            raise UserError(f"--shifts: {exc}") from None
    from model.draem.checkpoint import load_checkpoint

    ck = load_checkpoint(args.model)
    net = inference_net(ck, args.model, "fp32")
    va, _, vev = evaluate_split(ck, net, args.model, args.val_data, "val")
    sp = model_split(ck, args.model, args.data, "test", args.limit)
    labels, types = sp.label.numpy(), np.array([t or "" for t in sp.defect_type])
    if not labels.any() or labels.all():
        raise UserError(f"{args.data}: the test split needs good and defective parts")
    ch = Channels.of(ck.detector.config.priors)
    own = ck.meta.get("threshold")
    rows, per_type = [], {}
    for name in names:
        x = torch.from_numpy(shift(name, sp.priors.numpy(), ch))
        around = None
        if sp.around is not None:  # the frame around the view, shifted alike (its centre is the view's)
            a = sp.around.numpy()
            shifted = shift(name, a, ch)
            shifted[~np.isfinite(a)] = np.nan  # beyond the frame stays beyond it
            around = torch.from_numpy(shifted)
        ev = evaluate(net, EvalData(x, sp.object_mask, sp.defect_mask, sp.label, "rendered", sp.mask_known, around))
        rep = detection_by_type(labels, ev.scores, types, validation=(va.label.numpy(), vev.scores))
        good = ev.scores[labels == 0]
        rows.append({"shift": name, "image_auroc": auroc(labels.astype(bool), ev.scores),
                     "caught_1%": rep.overall.caught[0.01], "good_rejected_1%": rep.false_reject_observed[0.01],
                     "caught_5%": rep.overall.caught[0.05], "good_rejected_5%": rep.false_reject_observed[0.05],
                     "good_rejected_own": float((good > own).mean()) if own is not None else math.nan})
        per_type[name] = {t: r.image_auroc for t, r in rep.per_type.items()}
        print(f"{name}: image AUROC {rows[-1]['image_auroc']:.3f}, caught at 1 % {rows[-1]['caught_1%']:.0%} "
              f"({rows[-1]['good_rejected_1%']:.1%} of good parts rejected)", flush=True)
    columns = ["shift", "image_auroc", "caught_1%", "good_rejected_1%", "caught_5%", "good_rejected_5%",
               "good_rejected_own"]
    table = markdown_table(rows, columns)
    payload = {"model": args.model, "data": str(args.data), "val_data": str(args.val_data), "parts": len(labels),
               "good_parts": int((labels == 0).sum()), "threshold": own, "rows": rows, "per_type_auroc": per_type}
    json_path, _ = write_report(args.out, "shift", payload, table)
    _plot(rows, json_path.with_suffix(".png"))
    print(table + f"\n{json_path}")
    return 0


def _plot(rows: list[dict], path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.4))
    names = [r["shift"] for r in rows]
    axes[0].barh(names, [r["image_auroc"] for r in rows])
    axes[0].set_xlim(0.5, 1.0)
    axes[0].set_title("image AUROC", fontsize=9)
    axes[1].barh(names, [r["good_rejected_1%"] for r in rows], label="good parts rejected at the 1 % threshold")
    axes[1].barh(names, [r["caught_1%"] for r in rows], height=0.35, label="defective parts caught there")
    axes[1].set_xlim(0, 1)
    axes[1].legend(fontsize=7, loc="lower right")
    for ax in axes:
        ax.invert_yaxis()
        ax.tick_params(labelsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
