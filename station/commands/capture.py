"""``station capture``: record raw mosaics from the camera of ``station.toml`` (or ``--camera``) into the MVTec AD
layout, with the camera's settings, timestamps and brightness statistics (``station.capture``). With ``--model``
the statistics are compared with the range the model was trained (or adapted) on. With ``[second_camera]``, the
second camera's frames go to ``--second-out``, a twin folder, and with ``--second-model`` its statistics are compared
with that model's range."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from station.decision import SECOND_NAME

if TYPE_CHECKING:
    from station.drift import DriftMonitor


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("capture", help="record raw mosaics from the camera into the MVTec layout (for import/adapt)")
    p.add_argument("--camera", choices=("sim", "aravis"), default=None,
                   help="camera kind (default: [camera] kind in the config)")
    p.add_argument("--config", default="station.toml", help="station configuration (default station.toml)")
    p.add_argument("--frames", type=int, required=True, metavar="N",
                   help="number of parts to record (a frame each, or a frame per [camera] dome_segments entry)")
    p.add_argument("--out", required=True, metavar="DIR", help="MVTec-layout folder (created; frames are added)")
    p.add_argument("--label", default="good",
                   help="good (-> train/good), or a defect type for parts from the reject bin (-> test/<label>); "
                        "default good")
    p.add_argument("--split", default=None, choices=("train", "val", "test"),
                   help="override the split folder (default: train for good, test otherwise)")
    p.add_argument("--model", default=None,
                   help="checkpoint whose trained frame statistics to compare with (default: none)")
    p.add_argument("--second-out", default=None, metavar="DIR",
                   help="with [second_camera] enabled: the second camera's frames, a twin folder of --out (the same "
                        "names for the same parts; station split reads the two after station import)")
    p.add_argument("--second-model", default=None,
                   help="with [second_camera] enabled: the second camera's checkpoint whose trained frame statistics "
                        "to compare its frames with (default: none)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    import dataclasses

    from station.assembly import defect_pixel_map, open_camera
    from station.capture import SensorCalibration, capture
    from station.config import load_config
    from station.errors import UserError

    cfg = load_config(args.config)
    if args.camera:
        cfg = dataclasses.replace(cfg, camera=dataclasses.replace(cfg.camera, kind=args.camera))
    if cfg.priors.angles_deg is not None:
        raise UserError(f"{cfg.source}: [priors] angles_deg (a custom layout) cannot be recorded for import yet; "
                        f"use a named layout")
    monitor = _monitor(args.model, args.frames) if args.model else None
    keys = ("kind", "device", "pixel_format", "exposure_us", "gain_db", "width", "height", "offset_x", "offset_y",
            "trigger", "dome_segments")
    settings = {k: getattr(cfg.camera, k) for k in keys}
    second = cfg.second_camera.enabled
    if second != (args.second_out is not None):
        raise UserError(f"{cfg.source}: [second_camera] is enabled: name --second-out DIR for its frames (a twin "
                        "folder of --out)" if second else
                        f"--second-out {args.second_out}: {cfg.source} has no [second_camera] enabled")
    if args.second_model and not second:
        raise UserError(f"--second-model {args.second_model}: {cfg.source} has no [second_camera] enabled")
    second_monitor = _monitor(args.second_model, args.frames, second=True) if args.second_model else None
    defect_pixel_map(cfg)  # a map that cannot be read is one line naming the key, before the camera opens
    if second:
        defect_pixel_map(cfg, second=True)
    camera = open_camera(cfg)
    try:
        report = capture(camera, args.frames, args.out, args.label, args.split, settings, cfg.priors.layout,
                         software_trigger=cfg.camera.trigger == "software", bit_depth=cfg.priors.bit_depth,
                         segments=tuple(cfg.camera.dome_segments or ()),
                         on_frame=(lambda _n, s: _warn(monitor.update(s))) if monitor else None,
                         second_out=args.second_out,
                         second_settings={k: getattr(cfg.second_camera, k) for k in keys} if second else None,
                         calibration=SensorCalibration(cfg.camera.black_level, cfg.camera.defect_pixels),
                         second_calibration=SensorCalibration(cfg.second_camera.black_level,
                                                              cfg.second_camera.defect_pixels))
    finally:
        camera.close()
    print(report.describe())
    if monitor is not None and monitor.warning:
        print(f"warning: {monitor.warning}")
    if second_monitor is not None and report.second is not None:
        for stats in report.second.stats:  # compared after the capture: the first camera's warnings come as it runs
            second_monitor.update(stats)
        if second_monitor.warning:
            print(f"warning: {SECOND_NAME}: {second_monitor.warning}")
    return 0


def _monitor(model: str, frames: int, second: bool = False) -> DriftMonitor | None:
    """A ``station.drift.DriftMonitor`` over ``frames`` captured frames against the frame statistics ``model``
    records, saying what it compares with; None when the model records none. ``second``: the second camera's (named
    for it, its advice naming ``[second_camera]``'s keys)."""
    from model.draem.checkpoint import read_sidecar
    from station.drift import DriftMonitor, trained_range

    trained = trained_range(read_sidecar(model))
    named = f"{SECOND_NAME}: " if second else ""
    if trained is None:
        print(f"{named}{model}: no frame statistics recorded (trained before they were): nothing to compare")
        return None
    print(f"{named}{model} was trained on: {trained.describe()}")
    return DriftMonitor(trained, window=min(50, frames), min_frames=min(10, frames),
                        section="second_camera" if second else "camera")


def _warn(text: str | None) -> None:
    if text:
        print(f"\n{text}")
