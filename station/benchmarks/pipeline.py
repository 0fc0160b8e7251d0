"""Run time against error for the whole station: the real loop on held-out rendered parts over a grid of settings.

For each configuration (demosaic method x model checkpoint x precision x presence check on/off x drift monitors
on/off x prior set and early exit of a per-prior ensemble) a ``station.loop.Station`` inspects ``--parts`` parts from
the virtual camera (the dataset's test split, never trained on; the same frames in the same order for every
configuration; ``--empty-rate`` of them show no part, which needs a set rendered with ``station render --empty-rate``),
free-running as fast as processing allows (backpressure ``block``, no PLC), and logs to a temporary SQLite file.
A model that reads a frame per dome segment (photometric stereo) gets each part's frames, triggered one by one as
at the station (``[camera] dome_segments``); its latency counts every frame's grab and demosaic.
From the log:

- latency per frame = grab + demosaic + priors (+ presence check) + model (+ decision): the work from trigger to
  decision for one frame when frames arrive one cycle apart (queue waiting, which only exists when they arrive
  faster than that, is left out); p50 and p99 over every inspected frame, empty ones included (the check's
  saving);
- parts/s (frames/s) sustained over the run;
- image AUROC of the scores against the virtual camera's ground truth (frames that show a part and were judged),
  and the decisions' confusion at the model's threshold;
- members of a per-prior ensemble run per judged part (early exit: ``model.draem.early_exit``);
- prior sets (the paper's ablation, ``station.commands.eval.ABLATION``): a per-prior ensemble runs only the members
  of the set, and the station computes only their priors (no normal network without the normal prior); a fused
  model is one prior set (its own), so a fused ablation is one checkpoint per set in ``--models``;
- the presence check against ground truth: the fraction of empty frames skipped (logged "empty", model not run)
  and of frames showing a part wrongly skipped; and the check's own time per frame (p50);
- drift monitors (``--drift``, on by default as ``station run`` has them): each camera's frame statistics, computed
  with its priors (in ``priors_ms``) when its model records the range to compare them with; the row's ``drift`` says
  on, partly (one camera's model records none) or off.

With ``--second-model`` and ``--second-data`` (the twin set of ``--data``, seen by the second camera), every
configuration is a two-camera station (``[second_camera]``): both virtual cameras triggered per part, the second one's
frame judged by the second model (its presence rule ``row_contrast``) at the same time as the first's or after it
(``--pair-modes parallel,serial``; ``first-only``: the first camera alone, the peer), and the latency is the part's,
both cameras' work together. The row's AUROC and confusion stay the first camera's.

Writes JSON, a Markdown table and a Pareto plot (p99 latency against 1 - image AUROC), and names the
configurations on the front.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from station.commands.arguments import positive_int

PAIR_MODES = ("parallel", "serial", "first-only")
"""``--pair-modes``: how a station with a second camera judges a part's two frames, or the first camera alone."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--data", default="data/brick-v2", help="rendered set; its test split is inspected")
    p.add_argument("--models", default="model/weights/default", help="comma-separated checkpoint paths")
    p.add_argument("--methods", default="bilinear,superpixel,residual", help="demosaic methods")
    p.add_argument("--precisions", default="fp32,bf16",
                   help="fp32, bf16 (autocast), onnx (ONNX Runtime), int8 (ONNX Runtime, after station quantize)")
    p.add_argument("--early-exit", default="off",
                   help="per-prior ensembles: comma-separated off, exact (margin 0) or a margin in (0, 1]; "
                        "single networks run off only")
    p.add_argument("--prior-sets", default="all",
                   help="per-prior ensembles: comma-separated R, R+AoLP, R+AoLP+DoLP, all (the paper's ablation; "
                        "members the model lacks are skipped); fused models run their own priors")
    p.add_argument("--presence", default="on", help="presence check before the model: on, off, or on,off "
                   "(thresholds as [presence] in station.toml's defaults)")
    p.add_argument("--drift", default="on",
                   help="drift monitors: each camera's frame statistics against the range its model records, as "
                        "station run computes them (on; a model that records none has none), off, or on,off")
    p.add_argument("--around", default="on",
                   help="a variation model's registration reads the frame around its view (model.draem.roi.AROUND_PX "
                        "input px; as station run does: on), or only the view (off), or on,off")
    p.add_argument("--parts", type=positive_int, default=200, help="frames per configuration")
    p.add_argument("--defect-rate", type=float, default=0.5, help="fraction of the parts shown that are defective")
    p.add_argument("--empty-rate", type=float, default=0.0,
                   help="fraction of frames with no part in view (the set's test split needs empty samples)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--device", default="auto")
    p.add_argument("--second-model", default=None,
                   help="a second camera's checkpoint: every configuration runs two cameras per part (needs "
                        "--second-data)")
    p.add_argument("--second-data", default=None, help="the second camera's twin of --data (same seed and parts)")
    p.add_argument("--pair-modes", default="parallel",
                   help="with a second camera, comma-separated: parallel (its frame judged at the same time as the "
                        "first's), serial (after it), first-only (the first camera alone, the peer in the same run)")


def measure(data: str, model: str, method: str, precision: str, parts: int, defect_rate: float, seed: int,
            device: str, presence: bool = True, empty_rate: float = 0.0, early_exit: float | None = None,
            members: tuple[str, ...] | None = None, second: tuple[str, str] | None = None,
            parallel: bool = True, drift: bool = True, around: bool = True) -> dict:
    """One configuration through the real station loop; returns its row. ``second``: (checkpoint, twin set) of a
    second camera (module docstring), judged at the same time as the first (``parallel``) or after it; None: one
    camera. ``drift``: each camera's frame statistics computed and watched as ``station run`` does
    (``station.assembly.drift_monitor``). ``around``: the variation model reads the frame around its view (the
    model's ``around_px``) or only the view (0)."""
    from collections.abc import Mapping
    from typing import Any

    import numpy as np

    from drivers.camera import Camera, CameraConfig
    from drivers.virtual_camera import VirtualCamera, VirtualCameraConfig
    from model.draem.metrics import auroc
    from model.priors import get_layout
    from model.priors.photometric import frames_per_part
    from sim.dataset import open_dataset
    from station.assembly import drift_monitor
    from station.config import PresenceConfig
    from station.inspection_log import InspectionLog
    from station.inspector import Inspector
    from station.line_link import NoLink
    from station.loop import Station
    from station.model_detector import DraemDetector
    from station.presence import Presence, PresenceCheck, PresenceRule
    from station.second_camera import PairInspector

    detector = DraemDetector(model, device, precision, early_exit_margin=early_exit, members=members,
                             around_px=None if around else 0)
    detector.warm_up()
    detector.members_run = 0
    layout = get_layout(open_dataset(data).manifest.get("layout", "imx250mzr"))
    frames = frames_per_part(detector.dome_segments)  # a frame per dome segment: the station triggers each
    trigger = "free_run" if frames == 1 and second is None else "software"
    camera: Camera = VirtualCamera(CameraConfig(trigger=trigger, frame_rate_hz=1000.0, timeout_ms=10000,
                                                frames_per_part=frames),
                                   VirtualCameraConfig(data, defect_rate, split="test", seed=seed,
                                                       empty_rate=empty_rate))
    second_detector = None
    if second is not None:
        from drivers.camera_pair import CameraPair

        second_detector = DraemDetector(second[0], device, precision)
        second_detector.warm_up()
        camera = CameraPair(camera, VirtualCamera(CameraConfig(trigger="software", frame_rate_hz=1000.0,
                                                               timeout_ms=10000),
                                                  VirtualCameraConfig(second[1]), leader=camera),  # type: ignore[arg-type]
                            max_skew_ms=1e6)

    class TimedCheck(PresenceCheck):
        """Keeps the check's own time per frame in ms (the log folds it into ``priors_ms``)."""

        ms: list[float]

        def __init__(self, *args: Any, **kwargs: Any) -> None:
            super().__init__(*args, **kwargs)
            self.ms = []

        def __call__(self, priors: Mapping[str, np.ndarray]) -> Presence:
            t = time.perf_counter()
            out = super().__call__(priors)
            self.ms.append(1e3 * (time.perf_counter() - t))
            return out

    cfg = PresenceConfig()
    check = TimedCheck.from_config(cfg) if presence else None
    with tempfile.TemporaryDirectory() as tmp, InspectionLog(Path(tmp) / "log.sqlite") as log:
        camera.open()
        try:
            monitor = drift_monitor(detector) if drift else None
            inspector: Inspector | PairInspector = Inspector(detector, layout, method, presence=check,
                                                             segments=detector.dome_segments,
                                                             statistics=monitor is not None)
            second_monitor = None
            if second_detector is not None:
                second_check = PresenceCheck.from_config(cfg, PresenceRule.ROW_CONTRAST) if presence else None
                second_monitor = drift_monitor(second_detector, "second_camera") if drift else None
                inspector = PairInspector(inspector, Inspector(second_detector, layout, method, presence=second_check,
                                                               statistics=second_monitor is not None), parallel)
            station = Station(camera, inspector, NoLink(), log, cycle_time_ms=1e6, queue_size=1, backpressure="block",
                              grab_timeout_ms=10000, drift=monitor, second_drift=second_monitor)
            t = time.perf_counter()
            stats = station.run(parts, progress_every_s=1e9)
            seconds = time.perf_counter() - t
        finally:
            camera.close()
        rows = list(log.rows())
    inspected = [r for r in rows if r["demosaic_ms"] is not None]
    judged = [r for r in rows if r["score"] is not None and r["ground_truth_label"] is not None]
    lat = np.array([sum(r[k] or 0.0 for k in ("grab_ms", "demosaic_ms", "priors_ms", "model_ms"))
                    for r in inspected])
    y = np.array([r["ground_truth_label"] for r in judged])
    s = np.array([r["score"] for r in judged])
    # the threshold is the whole model's: a subset of an ensemble's members is measured by its scores alone
    flagged = s > detector.threshold if members is None else np.full(s.shape, np.nan)
    c = stats.confusion  # LiveStats: <truth>_<decision>, truth "none" = no part in view
    n_empty = sum(v for k, v in c.items() if k.startswith("none_"))
    n_parts = sum(v for k, v in c.items() if not k.startswith("none_"))
    model_ms = [r["model_ms"] for r in rows if r["model_ms"] is not None]
    return {"checkpoint": model, "second_checkpoint": second[0] if second else "",
            "pair_mode": ("parallel" if parallel else "serial") if second else "first-only",
            "model": detector.model_id, "fusion": detector.config.fusion,
            "priors": "+".join(detector.used_priors), "method": method, "precision": precision,
            "presence": "on" if presence else "off", "around": "on" if around else "off",
            "around_px": detector.predictor.around_px,
            "drift": ("on" if monitor is not None and (second is None or second_monitor is not None)
                      else "partly" if monitor is not None or second_monitor is not None else "off"),
            "early_exit": "off" if early_exit is None else "exact" if early_exit == 0 else f"margin {early_exit:g}",
            "members_per_part": detector.members_run / len(model_ms) if model_ms else float("nan"),
            "parts": len(rows), "empty_frames": n_empty,
            "judged": len(judged), "model_runs": len(model_ms),
            "p50_ms": float(np.percentile(lat, 50)), "p99_ms": float(np.percentile(lat, 99)),
            "model_p50_ms": float(np.median(model_ms)) if model_ms else float("nan"),
            "priors_p50_ms": float(np.median([(r["demosaic_ms"] or 0) + (r["priors_ms"] or 0) for r in inspected])),
            "presence_p50_ms": float(np.median(check.ms)) if check and check.ms else float("nan"),
            "empty_skipped": c["none_empty"] / n_empty if n_empty else float("nan"),
            "parts_skipped": (c["good_empty"] + c["bad_empty"]) / n_parts if n_parts else float("nan"),
            "parts_per_s": len(rows) / seconds, "image_auroc": auroc(y, s),
            "detected": float(flagged[y == 1].mean()) if (y == 1).any() else float("nan"),
            "flagged_good": float(flagged[y == 0].mean()) if (y == 0).any() else float("nan")}


def pareto_front(rows: list[dict]) -> list[int]:
    """Indices of rows no other row beats on both p99 latency (lower) and image AUROC (higher)."""
    front = []
    for i, r in enumerate(rows):
        if not any(o["p99_ms"] <= r["p99_ms"] and o["image_auroc"] >= r["image_auroc"]
                   and (o["p99_ms"], o["image_auroc"]) != (r["p99_ms"], r["image_auroc"]) for o in rows):
            front.append(i)
    return front


def label(r: dict) -> str:
    """A configuration in a few words (plot and front)."""
    ee = f"/early exit {r['early_exit']}" if r.get("early_exit", "off") != "off" else ""
    ck = Path(r.get("checkpoint") or r["model"].split("-")[0])
    name = ck.parent.name if ck.name in ("best", "last") else ck.name  # runs/train/<name>/best
    return (f"{name}/{r['priors']}/{r['method']}/{r['precision']}/"
            f"presence {r.get('presence', 'off')}{ee}{'/drift off' if r.get('drift') == 'off' else ''}"
            f"{'/view only' if r.get('around') == 'off' else ''}")


def _plot(out: Path, rows: list[dict], front: list[int]) -> str:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    for i, r in enumerate(rows):
        ax.scatter(r["p99_ms"], 1 - r["image_auroc"], c="C3" if i in front else "C0", s=25)
        ax.annotate(label(r),
                    (r["p99_ms"], 1 - r["image_auroc"]), fontsize=6)
    ax.axvline(100, color="k", ls=":", lw=0.8)
    ax.set(xlabel="p99 latency per part (ms)", ylabel="1 - image AUROC (held-out parts)",
           title="station run time against error (red: Pareto front)")
    fig.savefig(out / "pipeline.png", dpi=120, bbox_inches="tight")
    plt.close(fig)
    return "pipeline.png"


def _margin(text: str) -> float | None:
    """``--early-exit`` value -> ``DraemDetector``'s early_exit_margin."""
    from station.errors import UserError

    if text in ("off", "exact"):
        return None if text == "off" else 0.0
    try:
        m = float(text)
    except ValueError:
        m = -1.0
    if not 0 < m <= 1:
        raise UserError(f"--early-exit: {text!r} is not off, exact or a margin in (0, 1]")
    return m


def _members(cfg: dict, prior_set: str) -> tuple[str, ...] | bool | None:
    """``--prior-sets`` entry -> ``DraemDetector``'s members for a model with sidecar config ``cfg``: None for all
    its members (also every fused model's one configuration), False when the model does not run this set (lacks a
    member, or is fused)."""
    from station.errors import UserError
    from station.evaluation import ABLATION

    sets = dict(ABLATION)
    if prior_set not in sets:
        raise UserError(f"--prior-sets: {prior_set!r} is not one of {', '.join(sets)}")
    if cfg.get("fusion") != "ensemble":
        return None if prior_set == "all" else False
    have = set(cfg["priors"])
    wanted = have if prior_set == "all" else set(sets[prior_set])
    return None if wanted == have else sets[prior_set] if wanted < have else False


def run(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from model.draem.checkpoint import read_sidecar
    from station.benchmarks.report import markdown_table, write_report
    from station.errors import UserError

    if (args.second_model is None) != (args.second_data is None):
        raise UserError("--second-model and --second-data go together (a second camera's model and its twin set)")
    second = (args.second_model, args.second_data) if args.second_model else None
    pair_modes = args.pair_modes.split(",") if second else ["first-only"]
    if any(m not in PAIR_MODES for m in pair_modes):
        raise UserError(f"--pair-modes: {args.pair_modes!r}: comma-separated {', '.join(PAIR_MODES)}")
    presence, drift, around = args.presence.split(","), args.drift.split(","), args.around.split(",")
    for name, values in (("--presence", presence), ("--drift", drift), ("--around", around)):
        bad = [v for v in values if v not in ("on", "off")]
        if bad:
            raise UserError(f"{name}: {bad[0]!r} is not on or off")
    exits = [_margin(e) for e in args.early_exit.split(",")]
    models = args.models.split(",")
    cfgs = {m: read_sidecar(m)["model"] for m in models}  # each sidecar read once
    members = {(m, s): _members(cfgs[m], s) for m in models for s in args.prior_sets.split(",")}
    grid = [(m, meth, prec, pres, ee, mem, pm, dr, ar) for m in models for meth in args.methods.split(",")
            for prec in args.precisions.split(",") for pres in presence for ee in exits
            for mem in dict.fromkeys(v for (mm, _), v in members.items() if mm == m and v is not False)
            for pm in pair_modes for dr in drift for ar in around
            if ee is None or cfgs[m].get("fusion") == "ensemble"]
    rows = []
    for model, method, precision, pres, ee, mem, pm, dr, ar in tqdm(grid, desc="bench pipeline", unit="config"):
        rows.append(measure(args.data, model, method, precision, args.parts, args.defect_rate, args.seed,
                            args.device, pres == "on", args.empty_rate, ee, mem,
                            None if pm == "first-only" else second, pm == "parallel", dr == "on", ar == "on"))
    front = pareto_front(rows)
    for i, r in enumerate(rows):
        r["pareto"] = i in front
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    plot = _plot(out, rows, front)
    cols = ["checkpoint", *(["second_checkpoint", "pair_mode"] if second else []), "fusion", "priors",
            "method", "precision", "presence", "drift", "around_px", "early_exit", "members_per_part",
            "parts", "empty_frames", "model_runs", "p50_ms", "p99_ms",
            "priors_p50_ms", "model_p50_ms", "presence_p50_ms", "parts_per_s", "empty_skipped", "parts_skipped",
            "image_auroc", "detected", "flagged_good", "pareto"]
    table = (f"Station pipeline on {args.parts} held-out frames of {args.data} (test split), defect rate "
             f"{args.defect_rate}, empty rate {args.empty_rate}\n\n" + markdown_table(rows, cols))
    write_report(out, "pipeline", {"args": {k: v for k, v in vars(args).items() if k != "func"}, "rows": rows,
                                   "front": [rows[i] for i in front], "plot": plot}, table)
    print(table)
    print("front: " + "; ".join(f"{label(rows[i])} ({rows[i]['p99_ms']:.0f} ms p99, "
                                f"AUROC {rows[i]['image_auroc']:.3f})" for i in front))
    print(f"wrote {out / 'pipeline.json'}, {out / 'pipeline.md'}, {out / plot}")
    return 0
