"""``station.toml`` -> typed, validated configuration.

Each TOML table is a frozen dataclass below; a field's metadata holds its check (``choices``, ``range``,
``even``). A key left out takes the dataclass default; an ``X | None`` field left out is None ("not set").
Every problem is one ``ConfigError`` naming the file, table, key and reason. The shipped ``station.toml``
documents each key; a test keeps it equal to these defaults.
"""

from __future__ import annotations

import dataclasses
import tomllib
import types
import typing
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from model.draem.runtime import PRECISIONS
from model.priors import LAYOUTS, METHODS, MosaicLayout, get_layout
from model.priors.photometric import check_segments
from model.priors.photometric import frames_per_part as frames_of
from station.errors import UserError


class ConfigError(UserError):
    """The configuration file is unreadable or a key is unknown, of the wrong type or out of range."""


def _opt(default: Any, *, choices: tuple[Any, ...] | None = None, range: tuple[float, float] | None = None,
         even: bool = False) -> Any:
    return field(default=default, metadata={"choices": choices, "range": range, "even": even})


TRIGGERS = ("free_run", "software", "line0", "line1", "line2", "line3")

MAX_SEED = 2**63 - 1
"""The largest seed every generator takes (torch's is a signed 64-bit integer): ``[sim] seed`` and ``--seed``."""


@dataclass(frozen=True)
class CameraConfig:
    kind: str = _opt("sim", choices=("sim", "aravis"))
    device: str = ""
    pixel_format: str = "Mono8"
    width: int = _opt(0, range=(0, 16384), even=True)
    height: int = _opt(0, range=(0, 16384), even=True)
    offset_x: int = _opt(0, range=(0, 16384), even=True)
    offset_y: int = _opt(0, range=(0, 16384), even=True)
    exposure_us: float = _opt(10000.0, range=(1.0, 1e7))
    gain_db: float = _opt(0.0, range=(0.0, 48.0))
    frame_rate_hz: float = _opt(10.0, range=(0.01, 1000.0))
    packet_size: int = _opt(0, range=(0, 16384))
    trigger: str = _opt("software", choices=TRIGGERS)
    timeout_ms: int = _opt(1000, range=(1, 600000))
    reconnect: bool = True
    black_level: int = _opt(0, range=(0, 65534))
    """The code the camera's pixels read with no light (its pedestal, in the streamed pixel format's codes), removed
    from every frame before the demosaic with full scale kept (``model.priors.black_level``; ``station
    defect-pixels`` measures it from frames with the lens capped). 0: codes start at no light, as rendered."""
    defect_pixels: str = ""
    """A PNG of the camera's defective pixels (non-zero; the frame's size as streamed), filled from neighbours of the
    same polarizer angle before the demosaic (``model.priors.defect_pixels``; ``station defect-pixels`` finds them).
    "": none."""
    dome_segments: list[float] | None = None
    """Photometric stereo: azimuths (degrees, ``model.priors.photometric``) of the dome segments lit in turn, one
    frame each, in the order taken; None: one frame per part under the whole dome."""

    @property
    def frames_per_part(self) -> int:
        return frames_of(self.dome_segments)


@dataclass(frozen=True)
class AcquisitionConfig:
    queue_size: int = _opt(4, range=(1, 1024))
    backpressure: str = _opt("drop_oldest", choices=("drop_newest", "drop_oldest", "block"))
    cycle_time_ms: float = _opt(100.0, range=(1.0, 600000.0))
    max_frame_delay_ms: float | None = _opt(None, range=(1.0, 600000.0))


def frame_delay_limit_ms(max_frame_delay_ms: float | None, cycle_time_ms: float) -> float:
    """How long after a part's TRIG its frames may be exposed (ms): ``[acquisition] max_frame_delay_ms``, by default
    the cycle time."""
    return cycle_time_ms if max_frame_delay_ms is None else max_frame_delay_ms


@dataclass(frozen=True)
class PriorsConfig:
    layout: str = _opt("imx250mzr", choices=tuple(LAYOUTS))
    angles_deg: list[list[int]] | None = None
    demosaic: str = _opt("bilinear", choices=tuple(METHODS))
    bit_depth: int | None = _opt(None, range=(1, 16))

    def mosaic_layout(self) -> MosaicLayout:
        """The custom ``angles_deg`` layout when set, else the named ``layout``."""
        if self.angles_deg is None:
            return get_layout(self.layout)
        rows = self.angles_deg
        return MosaicLayout("custom", ((rows[0][0], rows[0][1]), (rows[1][0], rows[1][1])))


@dataclass(frozen=True)
class ModelConfig:
    path: str = "model/weights/default"
    device: str = _opt("auto", choices=("auto", "cpu", "cuda"))
    precision: str = _opt("auto", choices=PRECISIONS)
    early_exit_margin: float | None = _opt(None, range=(0.0, 1.0))
    fov_x_deg: float | None = _opt(None, range=(1.0, 179.0))


@dataclass(frozen=True)
class DecisionConfig:
    threshold: float | None = _opt(None, range=(0.0, 1.0))


PRESENCE_RULES = ("dolp_contrast", "row_contrast")
"""``[presence] rule`` and ``--presence-rule``: ``station.presence.PresenceRule``'s values, the default first (named
here so that the config and the CLI need not import the check, which imports OpenCV)."""


@dataclass(frozen=True)
class PresenceConfig:
    enabled: bool = True
    rule: str = _opt(PRESENCE_RULES[0], choices=PRESENCE_RULES)
    min_dolp_contrast: float = _opt(0.10, range=(0.0, 1.0))
    min_row_contrast: float = _opt(0.10, range=(0.0, 10.0))
    cell_px: int = _opt(12, range=(1, 4096))


@dataclass(frozen=True)
class SecondCameraConfig(CameraConfig):
    """``[second_camera]``: a second camera imaging each part with the first (``station.second_camera``). The
    camera keys are ``[camera]``'s, for this camera (``dome_segments`` not: one frame per part), and the rest are its
    own model, threshold, presence rule and, on the virtual camera, its twin of ``[sim] dataset``."""

    enabled: bool = False
    model: str = ""
    """Its model's checkpoint stem, as ``[model] path``; the ``[model]`` device and precision apply to both."""
    threshold: float | None = _opt(None, range=(0.0, 1.0))
    """Its threshold (``station split``), over its model's own."""
    presence_rule: str = _opt(PRESENCE_RULES[1], choices=PRESENCE_RULES)
    """Its presence rule, with ``[presence]``'s bounds and cell size: ``row_contrast`` for a camera looking level
    at the part."""
    dataset: str = ""
    """Virtual camera: the twin of ``[sim] dataset`` (the same seed and parts, rendered from this camera)."""
    parallel: bool = True
    """Judge its frame at the same time as the first camera's (``station.second_camera.PairInspector``)."""


@dataclass(frozen=True)
class IOConfig:
    mode: str = _opt("sim_plc", choices=("none", "sim_plc", "serial"))
    port: str = ""
    baudrate: int = _opt(115200, range=(300, 4000000))
    timeout_ms: int = _opt(500, range=(1, 60000))
    heartbeat_s: float = _opt(1.0, range=(0.0, 3600.0))


@dataclass(frozen=True)
class LogConfig:
    path: str = "runs/inspection.sqlite"
    save_rejects: bool = True
    image_dir: str = "runs/rejects"
    retention_days: float = _opt(30.0, range=(0.0, 36500.0))


@dataclass(frozen=True)
class SimConfig:
    dataset: str = ""
    defect_rate: float = _opt(0.2, range=(0.0, 1.0))
    empty_rate: float = _opt(0.0, range=(0.0, 1.0))
    seed: int = _opt(0, range=(0, MAX_SEED))


@dataclass(frozen=True)
class StationConfig:
    camera: CameraConfig = field(default_factory=CameraConfig)
    acquisition: AcquisitionConfig = field(default_factory=AcquisitionConfig)
    priors: PriorsConfig = field(default_factory=PriorsConfig)
    model: ModelConfig = field(default_factory=ModelConfig)
    decision: DecisionConfig = field(default_factory=DecisionConfig)
    presence: PresenceConfig = field(default_factory=PresenceConfig)
    second_camera: SecondCameraConfig = field(default_factory=SecondCameraConfig)
    io: IOConfig = field(default_factory=IOConfig)
    log: LogConfig = field(default_factory=LogConfig)
    sim: SimConfig = field(default_factory=SimConfig)
    source: str = field(default="<defaults>", compare=False)
    """Where this configuration was read from (for messages)."""


def _type_name(tp: Any) -> str:
    return {str: "a string", int: "an integer", float: "a number", bool: "true or false"}.get(tp, str(tp))


def _check_value(value: Any, tp: Any, where: str) -> Any:
    """``value`` converted to ``tp`` (int -> float allowed), or ConfigError."""
    origin = typing.get_origin(tp)
    if origin in (typing.Union, types.UnionType):
        return _check_value(value, next(a for a in typing.get_args(tp) if a is not type(None)), where)
    if origin is list:
        (item,) = typing.get_args(tp)
        if not isinstance(value, list):
            raise ConfigError(f"{where}: expected a list, got {value!r}")
        return [_check_value(v, item, f"{where}[{i}]") for i, v in enumerate(value)]
    if tp is float and isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    if (tp is int and isinstance(value, bool)) or not isinstance(value, tp):
        raise ConfigError(f"{where}: expected {_type_name(tp)}, got {value!r}")
    return value


def _build_table(cls: type, table: dict[str, Any], prefix: str) -> Any:
    """``cls`` from a TOML table; ``prefix`` starts every message ("station.toml: [camera] ")."""
    hints = typing.get_type_hints(cls)
    fields = {f.name: f for f in dataclasses.fields(cls) if f.name != "source"}
    unknown = sorted(set(table) - set(fields))
    if unknown:
        raise ConfigError(f"{prefix}{unknown[0]}: unknown key (known: {', '.join(fields)})")
    kwargs: dict[str, Any] = {}
    for name, value in table.items():
        f, key = fields[name], f"{prefix}{name}"
        if dataclasses.is_dataclass(hints[name]):
            if not isinstance(value, dict):
                raise ConfigError(f"{key}: expected a table [{name}], got {value!r}")
            kwargs[name] = _build_table(hints[name], value, f"{prefix}[{name}] ")
            continue
        value = _check_value(value, hints[name], key)
        meta = f.metadata
        if meta.get("choices") and value not in meta["choices"]:
            raise ConfigError(f"{key}: {value!r} is not one of {', '.join(map(repr, meta['choices']))}")
        if meta.get("range"):
            lo, hi = meta["range"]
            if not lo <= value <= hi:
                raise ConfigError(f"{key}: {value!r} is out of range [{lo:g}, {hi:g}]")
        if meta.get("even") and value % 2:
            raise ConfigError(f"{key}: {value!r} must be even (whole 2x2 polarizer superpixels)")
        kwargs[name] = value
    return cls(**kwargs)


def _check_layout(cfg: StationConfig, source: str) -> None:
    angles = cfg.priors.angles_deg
    if angles is None:
        return
    flat = sorted(a for row in angles for a in row)
    if len(angles) != 2 or any(len(row) != 2 for row in angles) or flat != [0, 45, 90, 135]:
        raise ConfigError(f"{source}: [priors] angles_deg: need [[a, b], [c, d]] holding 0, 45, 90, 135 once each, "
                          f"got {angles!r}")


GRAB_MARGIN_MS = 50.0
"""What ``[camera] timeout_ms`` must allow beyond the exposure for readout and transfer (``_check_timing``)."""


def _check_timing(cfg: StationConfig, source: str) -> None:
    """Key combinations under which a part would be judged on another part's frame."""
    if cfg.camera.trigger == "free_run" and cfg.io.mode != "none":
        raise ConfigError(f"{source}: [camera] trigger: 'free_run' with [io] mode {cfg.io.mode!r}: the PLC announces "
                          "parts, but a free-running camera's frames are not taken for them (a part would be judged "
                          "on a frame taken before it arrived); use 'software' or a line trigger, or [io] mode 'none'")
    frames = cfg.camera.frames_per_part
    if cfg.camera.dome_segments is not None:
        try:
            check_segments(cfg.camera.dome_segments)
        except ValueError as exc:
            raise ConfigError(f"{source}: [camera] dome_segments: {exc}") from None
    if frames > 1 and cfg.camera.trigger == "free_run":
        raise ConfigError(f"{source}: [camera] dome_segments: a frame per segment needs trigger = 'software' (the "
                          "station triggers each frame) or a line (the sequencer pulses the camera once per segment), "
                          "not 'free_run': nothing would tell which frame starts a part's set")
    exposure_ms = cfg.camera.exposure_us / 1e3
    delay_ms = frame_delay_limit_ms(cfg.acquisition.max_frame_delay_ms, cfg.acquisition.cycle_time_ms)
    if frames > 1 and cfg.camera.trigger.startswith("line") and frames * exposure_ms >= delay_ms:
        raise ConfigError(f"{source}: [acquisition] max_frame_delay_ms: {frames} exposures of {exposure_ms:g} ms take "
                          f"{frames * exposure_ms:g} ms, not within the {delay_ms:g} ms a part's frames may come after "
                          "its TRIG: every set's last frame would be taken for a missed pulse")
    if frames > 1 and frames * exposure_ms >= cfg.acquisition.cycle_time_ms:
        raise ConfigError(f"{source}: [camera] dome_segments: {frames} exposures of {exposure_ms:g} ms take "
                          f"{frames * exposure_ms:g} ms, the whole [acquisition] cycle_time_ms "
                          f"({cfg.acquisition.cycle_time_ms:g} ms): no part could be judged in time")
    if cfg.camera.timeout_ms < exposure_ms + GRAB_MARGIN_MS:
        raise ConfigError(f"{source}: [camera] timeout_ms: {cfg.camera.timeout_ms} ms does not cover the exposure "
                          f"({exposure_ms:g} ms) plus {GRAB_MARGIN_MS:g} ms for readout and transfer: a grab that "
                          "gives up before its frame arrives leaves that frame to be taken for the next part")


def _check_black_level(cfg: StationConfig, source: str) -> None:
    """``black_level`` below full scale of the codes a real camera streams (``[priors] bit_depth``, else the pixel
    format's); a virtual camera's bit depth is its set's, checked on its first frame (the part is rejected)."""
    from drivers.errors import PixelFormatError
    from drivers.pixel_formats import lookup

    cameras = [("camera", cfg.camera)] + ([("second_camera", cfg.second_camera)] if cfg.second_camera.enabled else [])
    for section, cam in cameras:
        if cam.black_level == 0 or cam.kind != "aravis":
            continue
        try:
            bits = cfg.priors.bit_depth or lookup(cam.pixel_format).bit_depth
        except PixelFormatError:
            continue  # a vendor format known by its frames only
        if cam.black_level >= 2**bits - 1:
            raise ConfigError(f"{source}: [{section}] black_level: {cam.black_level} is not below full scale "
                              f"{2**bits - 1} of {bits}-bit codes ({cam.pixel_format})")


def _check_second_camera(cfg: StationConfig, source: str) -> None:
    """``[second_camera]`` keys that cannot work with ``[camera]``'s."""
    second, where = cfg.second_camera, f"{source}: [second_camera]"
    if not second.enabled:
        return
    if not second.model:
        raise ConfigError(f"{where} model: must name the second camera's model when enabled = true")
    if second.dome_segments is not None:
        raise ConfigError(f"{where} dome_segments: the second camera takes one frame per part")
    if second.kind != cfg.camera.kind:
        raise ConfigError(f"{where} kind: {second.kind!r}, but [camera] kind is {cfg.camera.kind!r}: both cameras "
                          "must be virtual or both real")
    if second.kind == "sim" and not second.dataset:
        raise ConfigError(f"{where} dataset: the virtual second camera needs its twin of [sim] dataset (the same "
                          "seed and parts rendered from this camera)")
    if second.kind == "sim" and not cfg.sim.dataset:
        raise ConfigError(f"{source}: [sim] dataset: a virtual second camera needs a set of its own parts, not the "
                          "demo set, and its twin in [second_camera] dataset")
    if "free_run" in (cfg.camera.trigger, second.trigger):
        raise ConfigError(f"{where} trigger: two cameras need a trigger that starts each part ('software' or a line) "
                          "on both, not 'free_run': nothing would tell which frames are one part's")
    if (second.trigger == "software") != (cfg.camera.trigger == "software"):
        raise ConfigError(f"{where} trigger: {second.trigger!r} with [camera] trigger {cfg.camera.trigger!r}: both "
                          "'software' (the station triggers both) or both a line wired to the part's pulse")
    if second.timeout_ms < second.exposure_us / 1e3 + GRAB_MARGIN_MS:
        raise ConfigError(f"{where} timeout_ms: {second.timeout_ms} ms does not cover the exposure "
                          f"({second.exposure_us / 1e3:g} ms) plus {GRAB_MARGIN_MS:g} ms for readout and transfer")


def parse_config(text: str, source: str = "<string>") -> StationConfig:
    """Parse TOML ``text`` into a validated StationConfig; errors name ``source``."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{source}: not valid TOML: {exc}") from None
    cfg = _build_table(StationConfig, data, f"{source}: ")
    _check_layout(cfg, source)
    _check_timing(cfg, source)
    _check_second_camera(cfg, source)
    _check_black_level(cfg, source)
    return dataclasses.replace(cfg, source=source)


def load_config(path: str | Path) -> StationConfig:
    """Read and validate a ``station.toml``; a missing or unreadable file is a ConfigError naming it."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ConfigError(f"{p}: configuration file not found") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f"{p}: cannot read configuration: {exc}") from None
    return parse_config(text, str(p))
