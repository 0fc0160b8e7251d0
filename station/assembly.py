"""Build the station's parts from ``station.toml``: camera, PLC link, detector, inspection log.

Each builder fails at start-up with one line naming the key or file (``UserError`` and the packages' own errors),
never in the middle of a run.
"""

from __future__ import annotations

import dataclasses
import logging
from contextlib import ExitStack
from pathlib import Path

import numpy as np

from drivers.camera import Camera
from drivers.camera import CameraConfig as DriverCameraConfig
from model.priors.defect_pixels import read_defect_pixel_map
from station.config import ConfigError, StationConfig
from station.drift import DriftMonitor, trained_range
from station.inspection_log import InspectionLog
from station.inspector import Inspector
from station.line_link import LineLink, NoLink
from station.loop import Station
from station.model_detector import DraemDetector
from station.presence import PresenceCheck
from station.reject_store import RejectStore
from station.second_camera import PairInspector
from station.viewer import ViewerFeed

log = logging.getLogger(__name__)

DEMO_DATASET = "data/sim-demo-line-panel"
"""Where ``[sim] dataset = ""`` renders its parts on first use (``DEMO_PARTS`` of them, once)."""
DEMO_SCENE = tuple(Path(__file__).resolve().parents[1] / "sim" / "presets" / name
                   for name in ("line-polar.toml", "variation.toml", "panel.toml"))
"""The demo's scene: the line the shipped model was fitted for, with its variation and its bright-field panel
(``model/weights/README.md``; ``scripts/make-model.sh`` layers the same files)."""
DEMO_PARTS = 40
DEMO_SEED = 7
DEMO_SPP = 16
"""Seed and samples per pixel: the training set's spp; not a seed of its training (101), validation (303) or
held-out (1130) sets, so the demo shows parts the model never saw."""
DEMO_EMPTY_DATASET = "data/sim-demo-line-panel-empty"
"""The demo set with empty views, rendered instead (once) when ``[sim] empty_rate`` > 0 and ``dataset = ""``."""
DEMO_EMPTY_RATE = 0.25


def driver_camera_config(cfg: StationConfig, second: bool = False) -> DriverCameraConfig:
    """``[camera]`` (``second``: ``[second_camera]``) -> the drivers' ``CameraConfig`` (same names and units;
    ``kind`` picks the driver)."""
    camera = cfg.second_camera if second else cfg.camera
    names = {f.name for f in dataclasses.fields(DriverCameraConfig)}
    return DriverCameraConfig(**{k: v for k, v in dataclasses.asdict(camera).items() if k in names},
                              frames_per_part=camera.frames_per_part)


def ensure_sim_dataset(cfg: StationConfig) -> str:
    """The rendered set the virtual camera replays: ``[sim] dataset``, or the demo set, rendered when missing."""
    if cfg.sim.dataset:
        if not (Path(cfg.sim.dataset) / "manifest.json").is_file():
            raise ConfigError(f"{cfg.source}: [sim] dataset = {cfg.sim.dataset!r} is not a rendered set "
                              f"(no manifest.json; make one with `station render --out {cfg.sim.dataset}`)")
        return cfg.sim.dataset
    from sim.dataset import DatasetSpec, open_dataset, read_layers, render_set

    # the plain demo set stays as it was (make demo's first run); empty views only when asked for
    empty_rate = DEMO_EMPTY_RATE if cfg.sim.empty_rate > 0 else 0.0
    root = Path(DEMO_EMPTY_DATASET if empty_rate else DEMO_DATASET)
    if (root / "manifest.json").is_file() and len(open_dataset(root).indices(empty=None)) >= DEMO_PARTS:
        return str(root)
    print(f"[sim] dataset is empty: rendering {DEMO_PARTS} demo samples into {root} with Mitsuba (once; "
          f"a few seconds each" + (f"; {100 * empty_rate:.0f} % of them without the part" if empty_rate else "") + ")")
    spec = DatasetSpec.from_dict({"seed": DEMO_SEED, "width": 640, "height": 480, "spp": DEMO_SPP,
                                  "defect_fraction": 0.5, "defects_in_train": True, "empty_rate": empty_rate,
                                  **read_layers(DEMO_SCENE)})
    if empty_rate:
        _link_demo_parts(Path(DEMO_DATASET), root)
    render_set(root, spec, DEMO_PARTS)
    return str(root)


def _link_demo_parts(src: Path, dst: Path) -> None:
    """Hard-link the plain demo set's samples that show a part into the demo set with empty views: the same seed
    renders them identically (``sim.dataset.is_empty`` draws from its own stream), so only the empty views are
    rendered."""
    import os
    import shutil

    from sim.dataset import is_complete, is_empty, sample_dir

    if not (src / "manifest.json").is_file():
        return
    for i in range(DEMO_PARTS):
        if is_empty(DEMO_SEED, i, DEMO_EMPTY_RATE) or not is_complete(src, i) or is_complete(dst, i):
            continue
        final = sample_dir(dst, i)
        tmp = final.with_name(f"{final.name}.tmp-{os.getpid()}")  # renamed when whole, as sim.dataset writes
        try:
            shutil.copytree(sample_dir(src, i), tmp, copy_function=os.link)
            os.rename(tmp, final)
        except OSError:  # another file system: render it instead
            shutil.rmtree(tmp, ignore_errors=True)


def open_camera(cfg: StationConfig) -> Camera:
    """Open the camera ``[camera] kind`` names (not started); with ``[second_camera]`` enabled, both cameras as a
    ``drivers.camera_pair.CameraPair`` (the virtual second camera showing the first's parts from its twin set)."""
    dcfg = driver_camera_config(cfg)
    second: Camera | None = None
    if cfg.camera.kind == "sim":
        from drivers.virtual_camera import VirtualCamera, VirtualCameraConfig
        from sim.dataset import open_dataset

        dataset = ensure_sim_dataset(cfg)
        check_line_segments(cfg, open_dataset(dataset).dome_segments, f"the set {dataset} holds")
        check_set_black_level(cfg, dataset)
        camera: Camera = VirtualCamera(dcfg, VirtualCameraConfig(dataset, cfg.sim.defect_rate,
                                                                 seed=cfg.sim.seed, empty_rate=cfg.sim.empty_rate))
        if cfg.second_camera.enabled:
            twin = cfg.second_camera.dataset
            if not (Path(twin) / "manifest.json").is_file():
                raise ConfigError(f"{cfg.source}: [second_camera] dataset = {twin!r} is not a rendered set (no "
                                  "manifest.json)")
            check_set_black_level(cfg, twin, second=True)
            second = VirtualCamera(driver_camera_config(cfg, second=True), VirtualCameraConfig(twin),
                                   leader=camera)  # type: ignore[arg-type]
    else:
        from drivers.aravis_camera import AravisCamera

        camera = AravisCamera(dcfg)
        if cfg.second_camera.enabled:
            second = AravisCamera(driver_camera_config(cfg, second=True))
    if second is not None:
        from drivers.camera_pair import CameraPair
        from station.config import frame_delay_limit_ms
        from station.second_camera import SECOND_NAME

        camera = CameraPair(camera, second, frame_delay_limit_ms(cfg.acquisition.max_frame_delay_ms,
                                                                 cfg.acquisition.cycle_time_ms), SECOND_NAME)
    camera.open()
    return camera


def open_link(cfg: StationConfig, stack: ExitStack, max_parts: int | None = None) -> LineLink:
    """The PLC link ``[io] mode`` names, started; closed (and undelivered decisions logged) by ``stack`` if the
    station has not closed it. The simulated PLC announces ``max_parts`` parts (None: until closed), as a line
    that stops feeding when the run is over."""
    if cfg.io.mode == "none":
        return NoLink()
    from drivers.line_io import LineIO, LineIOConfig

    port = cfg.io.port
    if cfg.io.mode == "sim_plc":
        from drivers.plc_sim import SimulatedPLC

        # One part per camera frame period (per set of frames): the PLC paces the line, as on a real one.
        plc = SimulatedPLC(trigger_period_s=cfg.camera.frames_per_part / cfg.camera.frame_rate_hz,
                           heartbeat_s=cfg.io.heartbeat_s, max_triggers=max_parts)
        port = plc.station_port or ""
        stack.callback(plc.close)
    elif not port:
        raise ConfigError(f"{cfg.source}: [io] port: must name the PLC's serial port when mode = 'serial'")
    link = LineIO(LineIOConfig(port=port, baudrate=cfg.io.baudrate, timeout_ms=cfg.io.timeout_ms,
                               heartbeat_s=cfg.io.heartbeat_s))
    link.start()

    def close_link() -> None:
        for part_id, line in link.close():
            log.error("decision for part %s never reached the PLC: %s", part_id, line.strip())

    stack.callback(close_link)
    if cfg.io.mode == "sim_plc":
        plc.start()  # triggers start only once the station listens
    return link


def load_detector(cfg: StationConfig) -> DraemDetector:
    """The model ``[model]`` names, with ``[decision] threshold`` overriding its own; ConfigError when it reads other
    frames than ``[camera] dome_segments`` takes (photometric stereo: the same segments in the same order)."""
    detector = DraemDetector(cfg.model.path, cfg.model.device, cfg.model.precision, cfg.decision.threshold,
                             cfg.model.early_exit_margin, cfg.model.fov_x_deg)
    check_line_segments(cfg, detector.dome_segments, f"the model {cfg.model.path} reads")
    return detector


def load_second_detector(cfg: StationConfig) -> DraemDetector | None:
    """The second camera's model (``[second_camera] model``, its ``threshold`` over the model's own, ``[model]``'s
    device and precision), or None without a second camera."""
    second = cfg.second_camera
    if not second.enabled:
        return None
    detector = DraemDetector(second.model, cfg.model.device, cfg.model.precision, second.threshold,
                             cfg.model.early_exit_margin, cfg.model.fov_x_deg)
    if detector.dome_segments:
        raise ConfigError(f"{cfg.source}: [second_camera] model: {second.model} reads a frame per dome segment; the "
                          "second camera takes one frame per part")
    return detector


def check_line_segments(cfg: StationConfig, segments: tuple[float, ...], what: str) -> None:
    """ConfigError unless ``what`` ("the model M reads", "the set S holds") ``segments``, the frames ``[camera]
    dome_segments`` takes."""
    from model.priors.photometric import describe_segments, same_segments

    line = tuple(cfg.camera.dome_segments or ())
    if not same_segments(line, segments):
        want = f"[{', '.join(f'{a:g}' for a in segments)}]" if segments else "unset"
        raise ConfigError(f"{cfg.source}: [camera] dome_segments takes {describe_segments(line)}, but {what} "
                          f"{describe_segments(segments)}: set dome_segments {'= ' if segments else ''}{want}")


def check_set_black_level(cfg: StationConfig, dataset: str, second: bool = False) -> None:
    """ConfigError unless ``[camera] black_level`` (``second``: ``[second_camera]``'s) is the black level the set the
    virtual camera replays states (its frames carry that pedestal; ``station.datasets.set_black_level``)."""
    from sim.dataset import open_dataset
    from station.datasets import set_black_level

    section = "second_camera" if second else "camera"
    ours = (cfg.second_camera if second else cfg.camera).black_level
    theirs = set_black_level(dataset, open_dataset(dataset).manifest)
    if ours != theirs:
        raise ConfigError(f"{cfg.source}: [{section}] black_level: {ours}, but the set {dataset} states "
                          f"black_level {theirs} (its frames carry that pedestal): set black_level = {theirs}")


def defect_pixel_map(cfg: StationConfig, second: bool = False) -> np.ndarray | None:
    """``[camera] defect_pixels`` (``second``: ``[second_camera]``'s) read, or None when unset; ConfigError naming the
    file and key when it cannot be read."""
    section = "second_camera" if second else "camera"
    path = (cfg.second_camera if second else cfg.camera).defect_pixels
    if not path:
        return None
    try:
        return read_defect_pixel_map(path)
    except ValueError as exc:
        raise ConfigError(f"{cfg.source}: [{section}] defect_pixels: {exc}") from None


def presence_check(cfg: StationConfig, rule: str | None = None) -> PresenceCheck | None:
    """The ``[presence]`` check (``rule``: another than ``[presence] rule``, the second camera's), or None when
    disabled."""
    return PresenceCheck.from_config(cfg.presence, rule) if cfg.presence.enabled else None


def build_station(cfg: StationConfig, detector: DraemDetector, camera: Camera, link: LineLink,
                  inspection_log: InspectionLog, *, viewer: ViewerFeed | None = None,
                  rejects: RejectStore | None = None, second_detector: DraemDetector | None = None) -> Station:
    """The inspection loop with the ``[priors]``, ``[presence]``, ``[acquisition]`` and ``[camera]`` settings;
    with a viewer, the priors it shows are computed too. With ``[second_camera]`` enabled, the second camera's frames
    are judged by ``second_detector`` (loaded here when not given: ``load_second_detector``;
    ``station.second_camera``)."""
    if second_detector is None:
        second_detector = load_second_detector(cfg)
    drift = drift_monitor(detector)
    inspector: Inspector | PairInspector = Inspector(
        detector, cfg.priors.mosaic_layout(), cfg.priors.demosaic,
        display_priors=("intensity", "dolp", "aolp") if viewer else (), presence=presence_check(cfg),
        statistics=drift is not None, bit_depth=cfg.priors.bit_depth, segments=detector.dome_segments,
        defect_pixels=defect_pixel_map(cfg), black_level=cfg.camera.black_level)
    second_drift = None
    if second_detector is not None:
        second_drift = drift_monitor(second_detector, "second_camera")
        inspector = PairInspector(inspector, Inspector(
            second_detector, cfg.priors.mosaic_layout(), cfg.priors.demosaic,
            presence=presence_check(cfg, cfg.second_camera.presence_rule), statistics=second_drift is not None,
            bit_depth=cfg.priors.bit_depth, defect_pixels=defect_pixel_map(cfg, second=True),
            black_level=cfg.second_camera.black_level), cfg.second_camera.parallel)
    return Station(camera, inspector, link, inspection_log, cycle_time_ms=cfg.acquisition.cycle_time_ms,
                   queue_size=cfg.acquisition.queue_size, backpressure=cfg.acquisition.backpressure,
                   grab_timeout_ms=cfg.camera.timeout_ms, max_frame_delay_ms=cfg.acquisition.max_frame_delay_ms,
                   viewer=viewer, rejects=rejects, drift=drift, second_drift=second_drift)


def drift_monitor(detector: DraemDetector, section: str = "camera") -> DriftMonitor | None:
    """A drift check against the frame statistics the model records (``station train``, ``station adapt``), or
    None for a model that records none (said once in the log); ``section`` the table of the camera it watches."""
    trained = trained_range(detector.meta)
    if trained is None:
        log.info("model %s records no frame statistics: no drift check (station adapt records them)",
                 detector.model_id)
        return None
    return DriftMonitor(trained, section=section)
