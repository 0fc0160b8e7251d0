"""``station run``: the inspection station on the virtual camera (``--camera sim``) or a GenICam camera (``aravis``).

Everything comes from ``station.toml``; ``--camera`` only picks the camera kind. Start-up order is chosen so that
a bad model, log or camera stops the station before the PLC starts sending parts.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import logging
import threading
from contextlib import ExitStack
from pathlib import Path

log = logging.getLogger(__name__)


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("run", help="run the inspection station (virtual camera, or a real camera over Aravis)")
    p.add_argument("--camera", choices=("sim", "aravis"), default=None,
                   help="camera kind (default: [camera] kind in the config)")
    p.add_argument("--config", default="station.toml", help="station configuration (default station.toml)")
    p.add_argument("--frames", type=int, default=None, metavar="N", help="stop after N parts (default: until Ctrl-C)")
    p.add_argument("--viewer", action="store_true", help="show the live Qt viewer")
    p.add_argument("--summary-json", default=None, metavar="FILE", help="also write the final summary as JSON")
    p.set_defaults(func=run)


def confusion_table(confusion: dict[str, int]) -> str:
    """The decisions against the virtual camera's ground truth as a text table (``LiveStats.confusion`` keys):
    good and defective parts x pass and reject, plus a column "empty" and a row "no part" when there were
    frames skipped as empty or frames without a part."""
    from station.decision import Verdict

    g = lambda k: confusion.get(k, 0)  # noqa: E731
    truths = [("good part", "good"), ("defective part", "bad")]
    decisions = [Verdict.PASS, Verdict.REJECT]
    if any(k.startswith("none_") or k.endswith("_empty") for k in confusion):
        truths.append(("no part", "none"))
        decisions.append(Verdict.EMPTY)
    rows = [("", *decisions)] + [(name, *(g(f"{t}_{d}") for d in decisions)) for name, t in truths]
    return "\n".join(f"{r[0]:>16}" + "".join(f" {v!s:>8}" for v in r[1:]) for r in rows)


def run(args: argparse.Namespace) -> int:
    from drivers.camera_pair import CameraPair
    from station.assembly import build_station, load_detector, load_second_detector, open_camera, open_link
    from station.config import ConfigError, load_config
    from station.errors import UserError
    from station.inspection_log import InspectionLog
    from station.reject_store import RejectStore

    if args.frames is not None and args.frames < 1:
        raise UserError(f"--frames must be >= 1, got {args.frames}")
    cfg = load_config(args.config)
    if args.camera:  # both cameras' kind
        cfg = dataclasses.replace(cfg, camera=dataclasses.replace(cfg.camera, kind=args.camera),
                                  second_camera=dataclasses.replace(cfg.second_camera, kind=args.camera))
    detector = load_detector(cfg)
    print(f"model {detector.model_id}: priors {', '.join(detector.config.priors)}, threshold "
          f"{detector.threshold:.4g}, warm-up {detector.warm_up():.0f} ms per part on {detector.device}")
    second = load_second_detector(cfg)
    if second is not None:
        print(f"second camera's model {second.model_id}: priors {', '.join(second.config.priors)}, threshold "
              f"{second.threshold:.4g}, warm-up {second.warm_up():.0f} ms per part")
    if detector.threshold >= 1.0:  # scores lie in [0, 1] and reject when above the threshold
        log.warning("threshold %.4g rejects no part on its score: only parts that cannot be judged are rejected "
                    "([decision] threshold or the model's own)", detector.threshold)
    from station.heap import collect

    collect()  # what loading left, before any device opens (station.heap); the run then freezes what is alive
    if cfg.log.save_rejects and Path(cfg.log.image_dir).exists() and not Path(cfg.log.image_dir).is_dir():
        raise ConfigError(f"{cfg.source}: [log] image_dir: {cfg.log.image_dir} is a file, not a folder")
    with ExitStack() as stack:
        inspection_log = stack.enter_context(InspectionLog(cfg.log.path))
        rejects = RejectStore(cfg.log.image_dir) if cfg.log.save_rejects else None
        expired = inspection_log.apply_retention(cfg.log.retention_days)
        if expired and rejects is not None:
            rejects.delete(expired)
        camera = open_camera(cfg)
        stack.callback(camera.close)
        viewer = None
        if args.viewer:
            from station.viewer import ViewerFeed

            viewer = ViewerFeed()
        link = open_link(cfg, stack, args.frames)
        station = build_station(cfg, detector, camera, link, inspection_log, viewer=viewer, rejects=rejects,
                                second_detector=second)
        print(f"inspecting with camera {cfg.camera.kind}, PLC {cfg.io.mode}, log {cfg.log.path}"
              + (f", {args.frames} parts" if args.frames else ", until Ctrl-C"))
        if viewer is None:
            stats = station.run_until_signal(args.frames)
        else:
            from station.viewer import run_viewer

            failed: list[BaseException] = []  # what ended the station's thread, raised here as without a viewer

            def inspect() -> None:
                try:
                    station.run(args.frames)
                except BaseException as exc:
                    failed.append(exc)

            worker = threading.Thread(target=inspect, name="station", daemon=True)
            with station.stop_on_signals():  # Ctrl-C / SIGTERM stop the station; the window then closes itself
                worker.start()
                run_viewer(viewer, done=lambda: not worker.is_alive())  # until the window closes or the run ends
                station.stop()
                worker.join()
            if failed:
                raise failed[0]
            stats = station.stats
        camera_stats = camera.statistics().as_dict()
        if isinstance(camera, CameraPair):
            camera_stats["second_camera"] = {**camera.second_statistics().as_dict(), "unpaired": camera.unpaired}
    summary = {**stats.summary(), "confusion": dict(stats.confusion), "camera": camera_stats,
               "model_id": detector.model_id, "threshold": detector.threshold, "log": cfg.log.path,
               "stale_frames": station.stale_frames, "unrecorded_rows": station.unrecorded_rows,
               "collector_pause_max_ms": station.collector_pauses.longest_ms if station.collector_pauses else None,
               "plc_link": dataclasses.asdict(link.stats_snapshot()) if hasattr(link, "stats_snapshot") else None}
    print("\nsummary: " + ", ".join(f"{k} {v:.4g}" if isinstance(v, float) else f"{k} {v}"
                                    for k, v in stats.summary().items()))
    if stats.confusion:
        print("decisions against the virtual camera's ground truth:\n" + confusion_table(stats.confusion))
    if args.summary_json:
        with open(args.summary_json, "w") as f:
            json.dump(summary, f, indent=1, default=str)
    if station.fatal:
        raise UserError(f"station stopped: {station.fatal}")
    return 0
