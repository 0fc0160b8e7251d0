"""``station normals``: train the learned normal estimator on a rendered set's train split and compare it with the
physics baseline (diffuse shape from polarization) on the held-out test split.

Bridge: ``sim.dataset`` sample -> ``model.priors.compute_priors`` on the raw mosaic -> ``model.normals``. Every
method is scored on the same grid, the network's square view of the frame (``--roi``, default the station's
centre square, resized to ``--size``), against the renderer's ground-truth normals resized alike, over object
pixels pooled across the test split: mean and median angle (degrees), fractions within 11.25/22.5/30 degrees,
also per part. Rows: the net; SfP with the outward rule for the pi ambiguity (centre: the object mask's centroid
in the full frame); SfP with the ground-truth sign (an upper bound that isolates the ambiguity); the viewing
direction itself (n = v, what "facing the camera" scores); SfP at full resolution (its native grid). Writes
``normal_net.pt/.json``, ``normals.json``, ``normals.md``, ``normals.png`` (example maps) in ``--out``.
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

from station.commands.arguments import path_text, positive_int, seed
from station.errors import UserError

log = logging.getLogger(__name__)

PRIOR_NAMES = ("intensity", "dolp", "aolp", "aolp_cos", "aolp_sin")
METHODS = (("net", "learned U-Net"), ("sfp", "diffuse SfP, outward rule"),
           ("sfp_gt_sign", "diffuse SfP, ground-truth sign (upper bound)"), ("view", "n = viewing direction"))


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("normals", help="train the normal estimator; angular error of it and of physics SfP on test")
    p.add_argument("--data", required=True, help="rendered dataset folder with ground truth (station render --out)")
    p.add_argument("--train-minutes", type=float, default=10.0, help="training time limit in minutes")
    p.add_argument("--steps", type=positive_int, default=None, help="optimiser steps (default: until --train-minutes)")
    p.add_argument("--out", default="runs/normals", help="output folder")
    p.add_argument("--model", type=path_text, default=None,
                   help="evaluate this checkpoint (path without suffix) instead of training")
    p.add_argument("--size", type=positive_int, default=128,
                   help="network input side in pixels (DRAEM fast preset: 128)")
    p.add_argument("--roi", default="center", choices=("center", "object"),
                   help="square the network sees: center (the station's) or object (around the rendered mask)")
    p.add_argument("--base-width", type=int, default=16)
    p.add_argument("--levels", type=int, default=3, help="U-Net poolings")
    p.add_argument("--batch-size", type=int, default=8)
    p.add_argument("--lr", type=float, default=2e-3)
    p.add_argument("--seed", type=seed, default=0)
    p.add_argument("--device", default="auto", help="auto (CUDA if available), cpu, cuda, ...")
    p.add_argument("--threads", type=positive_int, default=None, help="torch CPU threads (default: torch's)")
    p.add_argument("--ior", type=float, default=1.5, help="refractive index for the SfP baseline")
    p.add_argument("--limit", type=positive_int, default=None, help="at most N samples per split (smoke runs)")
    p.add_argument("--no-plots", action="store_true")
    p.set_defaults(func=run)


def _part_names(manifest: dict) -> dict[int, str]:
    """Part label (``part_index`` value) -> part name, from the dataset's object; "part k" when unavailable."""
    try:
        from sim.meshes import object_from_config

        cfg = manifest.get("config", {})
        obj = object_from_config(cfg.get("mesh", ""), cfg.get("materials") or {}, cfg.get("mesh_scale", 1.0))
        return {i + 1: p.name for i, p in enumerate(obj.parts)}
    except Exception as exc:  # names are cosmetic: never fail the evaluation on them
        log.debug("part names unavailable: %s", exc)
        return {}


def _load(ds, split: str, size: int, roi: str, limit: int | None, ior: float, with_sfp: bool):
    """Samples of one split at the network's grid; with SfP (full frame, then cropped like the ground truth)."""
    import numpy as np
    import torch
    from tqdm import tqdm

    from model.draem.preprocess import crop_resize
    from model.normals.sfp import angular_error_deg, mask_centroid, sfp_normals, view_directions
    from model.normals.train import prepare_sample
    from model.priors import compute_priors

    idx = ds.indices(split)[:limit] if limit else ds.indices(split)
    if not idx:
        raise UserError(f"{ds.root}: no complete samples in split {split!r}")
    layout, bits = ds.manifest.get("layout", "imx250mzr"), ds.manifest.get("bit_depth")
    xs, ns, ms, parts, extras, full_err, examples, no_fov = [], [], [], [], [], [], [], 0
    for i in tqdm(idx, desc=f"loading {split}", unit="sample"):
        s = ds.load(i)
        if s.normal is None or s.object_mask is None:
            raise UserError(f"{ds.root}: sample {i} has no ground-truth normals or object mask (render with ground "
                            f"truth)")
        fov = (s.params.get("scene", {}).get("camera") or {}).get("fov_x_deg")
        no_fov += fov is None
        maps = compute_priors(s.raw, layout, priors=PRIOR_NAMES, bit_depth=bits)
        extra = ()
        if with_sfp:
            view = view_directions(s.object_mask.shape, fov)
            sfp = sfp_normals(maps["dolp"], maps["aolp"], view, ior, mask=s.object_mask, resolve="outward",
                              center=mask_centroid(s.object_mask))
            sfp_gt = sfp_normals(maps["dolp"], maps["aolp"], view, ior, mask=s.object_mask, resolve="reference",
                                 reference=s.normal)
            full_err.append(angular_error_deg(sfp, s.normal, s.object_mask))
            extra = (sfp, sfp_gt)
        smp = prepare_sample(maps, s.object_mask, size, fov, s.normal, roi, extra)
        box = smp["box"]
        pi = s.part_index if s.part_index is not None else s.object_mask.astype(np.uint8)
        labels = [int(k) for k in np.unique(pi) if k > 0]
        _, pm = crop_resize(np.zeros((1, *pi.shape), np.float32), box, size, ("intensity",),
                            tuple(pi == k for k in labels))
        part = torch.zeros((size, size), dtype=torch.uint8)
        for k, m in zip(labels, pm, strict=True):
            part[m] = k
        xs.append(smp["x"])
        ns.append(smp["normal"])
        ms.append(smp["mask"])
        parts.append(part)
        extras.append(smp["extra"])
        examples.append(i)
    if no_fov:
        log.warning("%d samples without a camera field of view: orthographic viewing directions", no_fov)
    out = {"x": torch.stack(xs), "normal": torch.stack(ns), "mask": torch.stack(ms), "part": torch.stack(parts),
           "index": examples}
    if with_sfp:
        out["sfp"] = torch.stack([e[0] for e in extras])
        out["sfp_gt_sign"] = torch.stack([e[1] for e in extras])
        out["sfp_full_err"] = np.concatenate(full_err)
    return out


def _plot(out: Path, te: dict, preds: dict, errs_maps: dict, n_examples: int = 4) -> str:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    n = te["x"].shape[0]
    pick = sorted({int(k) for k in np.rint(np.linspace(0, n - 1, min(n_examples, n)))})
    cols = [("intensity", None), ("ground truth", "gt"), ("SfP (outward)", "sfp"), ("net", "net"),
            ("SfP error", "sfp"), ("net error", "net")]
    fig, axes = plt.subplots(len(pick), len(cols), figsize=(1.9 * len(cols), 1.95 * len(pick)), squeeze=False)
    im = None
    for r, i in enumerate(pick):
        m = te["mask"][i].numpy()
        for c, (title, key) in enumerate(cols):
            ax = axes[r, c]
            if key is None:
                ax.imshow(te["x"][i, 0].numpy(), cmap="gray", vmin=0, vmax=1)
            elif title.endswith("error"):
                e = np.where(m, errs_maps[key][i], np.nan)
                ax.set_facecolor("0.85")
                im = ax.imshow(e, cmap="magma", vmin=0, vmax=90)  # fixed scale, degrees
            else:
                nm = (te["normal"] if key == "gt" else preds[key])[i].permute(1, 2, 0).numpy()
                rgb = np.where(m[..., None], (nm + 1) / 2, 0.85)
                ax.imshow(np.clip(rgb, 0, 1))
            ax.set_xticks([])
            ax.set_yticks([])
            if r == 0:
                ax.set_title(title, fontsize=8)
        axes[r, 0].set_ylabel(f"test {te['index'][i]}", fontsize=7)
    if im is not None:
        fig.colorbar(im, ax=axes.ravel().tolist(), shrink=0.6, pad=0.02, label="angular error (deg)")
    fig.suptitle("normals as RGB = (n + 1) / 2 (x right, y up, z toward camera); error 0..90 deg", fontsize=8)
    fig.savefig(out / "normals.png", dpi=110, bbox_inches="tight")
    plt.close(fig)
    return "normals.png"


def run(args: argparse.Namespace) -> int:
    import hashlib

    import numpy as np
    import torch

    from model.normals.net import NormalNetConfig, count_parameters, load_normal_net, save_normal_net
    from model.normals.sfp import angular_error_deg, summarize_errors
    from model.normals.train import NormalTrainConfig, predict_normals, train_normal_net
    from sim.dataset import open_dataset
    from station.benchmarks.report import markdown_table, write_report

    if args.train_minutes <= 0 and args.steps is None and args.model is None:
        raise UserError("--train-minutes must be > 0 (or give --steps, or --model to evaluate a checkpoint)")
    if args.threads:
        torch.set_num_threads(args.threads)
    out = Path(args.out)
    ds = open_dataset(args.data)
    sha = hashlib.sha256((Path(args.data) / "manifest.json").read_bytes()).hexdigest()
    train_info: dict = {}
    if args.model:
        net, meta = load_normal_net(args.model)
        ck = Path(args.model)
        size, roi = net.config.input_size_px, net.config.roi
        train_info = {"checkpoint": str(ck), **meta.get("train", {})}
    else:
        cfg = NormalNetConfig(args.base_width, args.levels, input_size_px=args.size, roi=args.roi)
        size, roi = cfg.input_size_px, cfg.roi
        tr = _load(ds, "train", size, roi, args.limit, args.ior, with_sfp=False)
        tc = NormalTrainConfig(steps=args.steps, max_minutes=args.train_minutes if args.train_minutes > 0 else None,
                               batch_size=args.batch_size, lr=args.lr, seed=args.seed, device=args.device,
                               threads=args.threads)
        log.info("normal net: %d train samples at %dx%d (roi %s)", tr["x"].shape[0], size, size, roi)
        res = train_normal_net(tr["x"], tr["normal"], tr["mask"], cfg, tc)
        del tr
        cfg_info = {("steps_limit" if k == "steps" else k): v for k, v in res.config.items()}
        train_info = {**cfg_info, "steps": res.steps, "seconds": round(res.seconds, 1), "loss_first": res.loss_first,
                      "loss_last": res.loss_last, "history": res.history, "torch_threads": torch.get_num_threads(),
                      "parameters": count_parameters(res.net)}
        ck = out / "normal_net"
        save_normal_net(ck, res.net, sha, train_info)
        net, _ = load_normal_net(ck)  # evaluate what was written
    te = _load(ds, "test", size, roi, args.limit, args.ior, with_sfp=True)
    preds = {"net": predict_normals(net, te["x"]), "sfp": te["sfp"], "sfp_gt_sign": te["sfp_gt_sign"],
             "view": te["x"][:, 4:7]}
    maps = {k: angular_error_deg(v.permute(0, 2, 3, 1).numpy(), te["normal"].permute(0, 2, 3, 1).numpy())
            for k, v in preds.items()}
    mask = te["mask"].numpy()
    names = _part_names(ds.manifest)
    grid = f"{roi} {size}x{size}"
    rows, part_rows = [], []
    for key, desc in METHODS:
        rows.append({"method": key, "description": desc, "grid": grid, **summarize_errors(maps[key][mask])})
        for k in sorted(int(v) for v in torch.unique(te["part"]) if v > 0):
            pm = mask & (te["part"].numpy() == k)
            part_rows.append({"method": key, "part": names.get(k, f"part {k}"),
                              **summarize_errors(maps[key][pm])})
    rows.append({"method": "sfp_full_res", "description": "diffuse SfP, outward rule, full frame",
                 "grid": "full frame", **summarize_errors(te["sfp_full_err"])})
    out.mkdir(parents=True, exist_ok=True)
    files = [] if args.no_plots else [_plot(out, te, preds, maps)]
    trained = (f"trained {train_info['steps']} steps in {train_info['seconds'] / 60:.1f} min on "
               f"{train_info.get('device')} ({train_info.get('n_train')} train samples, batch "
               f"{train_info.get('batch_size')}, seed {train_info.get('seed')})" if "seconds" in train_info
               else "training record not in the sidecar")
    head = (f"# Normal estimation on {args.data} (test split, {te['x'].shape[0]} samples, object pixels pooled)\n\n"
            f"Net {ck}: {trained}.\n"
            + f"SfP: diffuse model, refractive index {args.ior}. Angles in degrees.\n\n")
    cols = ["method", "grid", "n_px", "mean_deg", "median_deg", "p90_deg", "within_11.25", "within_22.5",
            "within_30", "description"]
    table = head + markdown_table(rows, cols) + "\n## By part\n\n" + markdown_table(
        part_rows, ["method", "part", "n_px", "mean_deg", "median_deg", "within_22.5"])
    payload = {"data": str(args.data), "data_manifest_sha256": sha, "split": "test", "n_samples": te["x"].shape[0],
               "samples": te["index"], "ior": args.ior, "grid": grid, "checkpoint": str(ck),
               "train": {k: v for k, v in train_info.items() if k != "history"},
               "loss_history": train_info.get("history"), "rows": rows, "by_part": part_rows, "plots": files}
    jp, mp = write_report(out, "normals", payload, table)
    print(table)
    print(f"wrote {jp}, {mp}" + "".join(f", {out / f}" for f in files) + f"; checkpoint {ck}.pt/.json")
    return 0 if np.isfinite(rows[0]["mean_deg"]) else 1
