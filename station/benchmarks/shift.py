"""Accuracy when the frames differ from the renders: a model on a held-out set whose priors are changed as another
renderer, lens or camera would change them, with its validation thresholds held fixed (a line that has not adapted).

Each shift is a pure function on the stacked priors at the model's input (after the region crop and resize:
``model.draem.config.channel_slices``), with the project's conventions (``model.priors.conventions``): intensity in
full-scale units, DoLP in [0, 1], AoLP as (cos 2a, sin 2a), a counted counter-clockwise from image right. Per shift:
image AUROC, the share of defective parts caught and of good parts rejected at the thresholds that reject 1 % and 5 %
of the good validation parts, the share rejected at the model's own threshold, and image AUROC per defect type. The
unchanged row is what ``station eval`` reports on the same parts. What it does not cover: noise (a noisier frame is
judged against its own noise level: ``model.draem.variation``, docs/results/2026-11-24-noise-level.md) and a line
whose geometry or light differs (render it: docs/results/2026-11-25-gradient-dome.md)."""

from __future__ import annotations

import argparse
import math
from dataclasses import dataclass

import numpy as np

SHIFTS = ("none", "dolp x0.5", "dolp x2", "aolp +5 deg", "gamma 0.8", "gamma 1.25", "exposure x1.3", "blur 0.5 px",
          "blur 1 px")
"""Every shift ``station bench shift`` runs by default, by name (``shift``)."""


@dataclass(frozen=True)
class Channels:
    """Where intensity, DoLP and AoLP's (cos, sin) lie in a model's input (None when it does not read the prior)."""

    intensity: int | None
    dolp: int | None
    aolp: int | None

    @classmethod
    def of(cls, priors: tuple[str, ...]) -> Channels:
        from model.draem.config import channel_slices

        s = channel_slices(priors)
        return cls(*(s[p].start if p in s else None for p in ("intensity", "dolp", "aolp")))


def _stokes(x: np.ndarray, ch: Channels) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(N, C, H, W) priors -> S0, S1, S2 (N, H, W): S1, S2 = I DoLP (cos 2a, sin 2a)."""
    i = x[:, ch.intensity] if ch.intensity is not None else np.ones(x[:, 0].shape, np.float32)
    p = x[:, ch.dolp] if ch.dolp is not None else np.zeros_like(i)
    c, s = (x[:, ch.aolp], x[:, ch.aolp + 1]) if ch.aolp is not None else (np.ones_like(i), np.zeros_like(i))
    return i, i * p * c, i * p * s


def _from_stokes(x: np.ndarray, ch: Channels, s0: np.ndarray, s1: np.ndarray, s2: np.ndarray) -> np.ndarray:
    """Write S0, S1, S2 back as the model's priors, as the camera's priors are computed (``model.priors.stokes``:
    DoLP in [0, 1] and 0 on dark pixels; AoLP (1, 0) where it is undefined)."""
    from model.priors.stokes import aolp_vector, dolp

    out = x.copy()
    if ch.intensity is not None:
        out[:, ch.intensity] = s0
    if ch.dolp is not None:
        out[:, ch.dolp] = dolp(s0, s1, s2)
    if ch.aolp is not None:
        out[:, ch.aolp], out[:, ch.aolp + 1] = aolp_vector(s1, s2)
    return out


KINDS = ("none", "dolp", "aolp", "gamma", "exposure", "blur")


def parse(name: str) -> tuple[str, float]:
    """A shift's name -> (kind, its number): "dolp x2" -> ("dolp", 2.0), "none" -> ("none", 0.0); ValueError naming
    the shift otherwise (an unknown kind, a missing or non-finite number)."""
    kind, _, value = name.strip().partition(" ")
    try:
        number = 0.0 if kind == "none" else float(value.split()[0].lstrip("x+"))
    except (IndexError, ValueError):
        number = math.nan
    if kind not in KINDS or not math.isfinite(number) or (kind != "aolp" and number < 0):
        raise ValueError(f"unknown shift {name!r}: e.g. {', '.join(SHIFTS)}")
    return kind, number


def shift(name: str, x: np.ndarray, ch: Channels) -> np.ndarray:
    """``x`` (N, C, H, W) float32 priors changed by shift ``name`` (``SHIFTS``); finite wherever ``x`` is:
    - ``dolp xK``: DoLP times K, clipped to 1 (a material or renderer that polarizes less or more, or a polarizer
      array with another extinction ratio);
    - ``aolp +D deg``: AoLP plus D degrees (the polarizer grid mounted rotated, or another angle convention);
    - ``gamma G``: intensity I -> I^G (another tone response; a camera that is not linear);
    - ``exposure xK``: the four polarizer readings times K, each clipped at full scale 1, and the priors again from
      them (a brighter line: where a reading clips, DoLP falls);
    - ``blur S px``: a Gaussian of sigma S input pixels over S0, S1 and S2 (a softer lens or another
      anti-aliasing; polarization blurs linearly in the Stokes vector, not in DoLP or AoLP)."""
    import cv2

    x = np.nan_to_num(np.asarray(x, np.float32), nan=0.0, posinf=1.0, neginf=0.0)
    kind, number = parse(name)
    if kind == "none":
        return x.copy()
    out = x.copy()
    if kind == "dolp" and ch.dolp is not None:
        out[:, ch.dolp] = np.clip(x[:, ch.dolp] * number, 0.0, 1.0)
    elif kind == "aolp" and ch.aolp is not None:
        t = math.radians(2 * number)
        c, s = x[:, ch.aolp], x[:, ch.aolp + 1]
        out[:, ch.aolp], out[:, ch.aolp + 1] = c * math.cos(t) - s * math.sin(t), c * math.sin(t) + s * math.cos(t)
    elif kind == "gamma" and ch.intensity is not None:
        out[:, ch.intensity] = np.clip(x[:, ch.intensity], 0.0, None) ** number
    elif kind == "exposure" and ch.intensity is not None:
        # the four polarizer readings (the brightest is I (1 + DoLP)), scaled and clipped at full scale, then the
        # Stokes vector again from them; the camera's Stokes are twice these (intensity is S0 / 2)
        from model.priors.conventions import POLARIZER_ANGLES_DEG
        from model.priors.stokes import intensities_to_stokes, stokes_to_intensity

        s0, s1, s2 = (2 * number * a for a in _stokes(x, ch))
        angles = np.radians(POLARIZER_ANGLES_DEG)
        readings = np.stack([np.clip(stokes_to_intensity(s0, t, s1, s2), 0.0, 1.0) for t in angles])
        out = _from_stokes(x, ch, *(intensities_to_stokes(readings) / 2))
    elif kind == "blur":
        s0, s1, s2 = (np.stack([cv2.GaussianBlur(im, (0, 0), number, borderType=cv2.BORDER_REPLICATE) for im in a])
                      for a in _stokes(x, ch))
        out = _from_stokes(x, ch, s0, s1, s2)
    return np.nan_to_num(out, nan=0.0, posinf=1.0, neginf=0.0).astype(np.float32)


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
        ev = evaluate(net, EvalData(x, sp.object_mask, sp.defect_mask, sp.label, "rendered", sp.mask_known))
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
