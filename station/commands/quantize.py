"""``station quantize``: int8 copies of a checkpoint's networks for ONNX Runtime on CPU (``[model] precision =
"int8"``), calibrated on good parts of the training split of the set it trained on, and what that costs on the
validation split (image / pixel AUROC and decisions at the model's threshold, fp32 against int8). That check is
recorded in ``int8.json``: ``precision = "auto"`` runs int8 only where it changed few decisions
(``model.draem.quantize.AUTO_MAX_CHANGED``)."""

from __future__ import annotations

import argparse

from station.errors import UserError


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("quantize", help="int8 copies of a model's networks (ONNX Runtime), calibrated on its training "
                                        "set")
    p.add_argument("--model", required=True, help="checkpoint path without suffix (e.g. model/weights/default)")
    p.add_argument("--data", required=True, help="the rendered set the checkpoint was trained on")
    p.add_argument("--samples", type=int, default=32, help="good training parts to calibrate activation ranges on")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    import numpy as np

    from model.draem.checkpoint import load_checkpoint
    from model.draem.evaluate import EvalData, evaluate
    from model.draem.quantize import fit_for_auto, int8_dir, quantize_detector, record_check
    from station.benchmarks.report import markdown_table
    from station.datasets import check_trained_on
    from station.evaluation import inference_net, model_split

    if args.samples < 1:
        raise UserError(f"--samples {args.samples}: at least 1")
    sha = check_trained_on(args.model, args.data)  # before loading anything heavy
    ck = load_checkpoint(args.model)
    calib = model_split(ck, args.model, args.data, "train", args.samples)
    folder = quantize_detector(ck.detector, calib.priors, int8_dir(args.model), ck.meta["weights_sha256"],
                               {"data": str(args.data), "data_manifest_sha256": sha, "split": "train"})
    val = model_split(ck, args.model, args.data, "val")
    data = EvalData(val.priors, val.object_mask, val.defect_mask, val.label, "rendered")
    ev = {p: evaluate(inference_net(ck, args.model, p), data) for p in ("fp32", "int8")}
    labels = val.label.numpy()
    rows = [{"precision": p, "image_auroc": e.metrics["image_auroc"] if 0 < labels.sum() < len(labels) else None,
             "pixel_auroc": e.metrics["pixel_auroc"],
             "max_score_diff": float(np.abs(e.scores - ev["fp32"].scores).max()),
             "decisions_changed": int(((e.scores > ck.threshold) != (ev["fp32"].scores > ck.threshold)).sum())
             if ck.threshold is not None else None} for p, e in ev.items()]
    record_check(folder, len(labels), rows[1]["decisions_changed"], rows[1]["max_score_diff"])
    print(f"wrote {folder} (calibrated on {calib.priors.shape[0]} good training parts of {args.data}); "
          f"validation split, {len(labels)} parts:\n")
    print(markdown_table(rows, ["precision", "image_auroc", "pixel_auroc", "max_score_diff", "decisions_changed"]))
    fit, why = fit_for_auto(folder)
    print(f"\n{why}: precision \"auto\" {'runs int8' if fit else 'runs fp32; int8 only when asked for'}")
    return 0
