"""The camera boundary: one Protocol every camera implements (Aravis/GenICam, virtual), its configuration and
statistics, and the small helpers drivers share (frame id unwrapping, reconnect back-off).

Life cycle::

    cam = AravisCamera(CameraConfig(device="127.0.0.1"))   # nothing happens yet
    with cam:                       # open(): connect and apply the config
        cam.start()                 # buffers allocated, acquisition running
        cam.trigger()               # trigger="software" only
        frame = cam.grab(timeout_ms=1000)
        cam.stop()
    cam.statistics()                # still readable after close

Failure rules (every implementation keeps them; tests hold them to it):

- ``open()``: ``CameraNotFound`` when nothing answers to ``config.device``; ``CameraConfigError`` when a value
  cannot be applied (names the feature and value); ``CameraError`` for anything else. A failed open leaves the
  object closed (``close()`` is still safe).
- ``configure(config)``: only while stopped (``CameraError`` otherwise); ``CameraConfigError`` naming the feature.
  Values the camera adjusts (a packet size, a frame rate bound) are logged, not raised.
- ``start()``: ``CameraError`` if not open. ``stop()`` / ``close()`` never raise, are idempotent, and are safe
  after the camera is lost.
- ``trigger()``: ``CameraError`` unless ``config.trigger == "software"`` and started.
- ``grab(timeout_ms)``: returns only complete frames. ``CameraTimeout`` when no complete frame arrives in
  ``timeout_ms`` (default ``config.timeout_ms``): the camera stays usable. Incomplete frames (missing packets,
  size mismatch...) and frames that arrive behind a newer one are counted in ``statistics().failed`` and logged,
  never delivered: frame ids only increase. Frames lost before they
  reached the host (gaps in frame ids) are counted in ``dropped``. ``CameraLost`` when the device stops answering
  and, with ``config.reconnect``, every reconnect attempt failed; the statistics are kept. ``CameraError`` if
  not started.
- ``statistics()``: a snapshot copy, valid at any time, also after close or loss.
"""

from __future__ import annotations

import collections
import dataclasses
import logging
from collections.abc import Iterator
from dataclasses import dataclass, field
from types import TracebackType
from typing import Protocol, runtime_checkable

from drivers.errors import CameraConfigError
from drivers.frame import Frame

log = logging.getLogger(__name__)

TRIGGERS = ("free_run", "software", "line0", "line1", "line2", "line3")
"""free_run: the camera runs at ``frame_rate_hz``; software: one frame per ``trigger()``; lineN: one frame per
rising edge on hardware input line N."""


@dataclass(frozen=True)
class CameraConfig:
    """What a camera driver needs; ``station.config.CameraConfig`` maps onto it (same names and units).

    device          Aravis: device id ("Vendor-Model-Serial"), serial number, or IPv4 address; "" = the only
                    camera found. Virtual camera: ignored.
    pixel_format    wire format name (``drivers.pixel_formats.FORMATS``).
    width, height   region of interest in pixels; 0 = the full sensor. Offsets and sizes must be even so the
                    region keeps whole 2x2 polarizer superpixels.
    exposure_us     exposure time in microseconds.
    gain_db         analogue gain in decibels.
    frame_rate_hz   free-run frame rate; with a trigger, the upper bound.
    packet_size     GigE Vision stream packet size in bytes; 0 = negotiate the largest the path carries.
    trigger         one of ``TRIGGERS``.
    timeout_ms      default grab timeout.
    reconnect       reconnect with back-off when the camera is lost (``reconnect_attempts`` tries, waiting
                    ``reconnect_backoff_s`` doubled after each failure up to ``reconnect_backoff_max_s``).
    n_buffers       stream buffer pool size.
    frames_per_part frames that make one part (photometric stereo: one per dome segment, lit in turn by a light
                    sequencer stepped by the camera's exposure output, reset by the PLC with each part); more than
                    one needs a trigger that starts each set: ``"software"`` (the station triggers each frame of
                    a part's set itself) or a line (the sequencer pulses the camera once per segment; a pulse the
                    camera misses is told by the time its successor was exposed, ``station.loop``). The virtual
                    camera plays a set rendered with ``station render --dome-segments`` frame by frame.
    """

    device: str = ""
    pixel_format: str = "Mono8"
    width: int = 0
    height: int = 0
    offset_x: int = 0
    offset_y: int = 0
    exposure_us: float = 10000.0
    gain_db: float = 0.0
    frame_rate_hz: float = 10.0
    packet_size: int = 0
    trigger: str = "software"
    timeout_ms: int = 1000
    reconnect: bool = True
    reconnect_attempts: int = 5
    reconnect_backoff_s: float = 0.5
    reconnect_backoff_max_s: float = 8.0
    n_buffers: int = 8
    frames_per_part: int = 1

    def __post_init__(self) -> None:
        if self.trigger not in TRIGGERS:
            raise CameraConfigError(f"camera trigger {self.trigger!r}: must be one of {', '.join(TRIGGERS)}")
        for name in ("width", "height", "offset_x", "offset_y"):
            value = getattr(self, name)
            if value < 0 or value % 2:
                raise CameraConfigError(f"camera {name} = {value}: must be even and >= 0 (whole 2x2 superpixels)")
        for name in ("exposure_us", "frame_rate_hz", "timeout_ms", "n_buffers", "frames_per_part"):
            if getattr(self, name) <= 0:
                raise CameraConfigError(f"camera {name} = {getattr(self, name)}: must be > 0")
        if self.frames_per_part > 1 and self.trigger == "free_run":
            raise CameraConfigError(f"camera frames_per_part = {self.frames_per_part} needs a software or line "
                                    "trigger, not 'free_run': nothing would tell which frame starts a part's set")
        if self.gain_db < 0 or self.packet_size < 0 or self.reconnect_attempts < 0:
            raise CameraConfigError("camera gain_db, packet_size and reconnect_attempts must be >= 0")


@dataclass
class CameraStatistics:
    """Counters since the camera object was made (they survive stop/start, reconnects and close).

    completed        frames delivered by ``grab``.
    failed           frames that arrived incomplete (missing packets, size mismatch, ...) or out of order ("late":
                     behind a newer frame): counted, never delivered.
    dropped          frames that never reached the host: gaps in the frame ids, buffer underruns.
    resent           packets the host asked the camera to resend (GigE Vision).
    missing_packets  packets that never arrived even after resend requests (GigE Vision).
    timeouts         ``grab`` calls that raised ``CameraTimeout``.
    reconnects       successful reconnects after a loss.
    failed_by_status incomplete frames by buffer status name.
    """

    completed: int = 0
    failed: int = 0
    dropped: int = 0
    resent: int = 0
    missing_packets: int = 0
    timeouts: int = 0
    reconnects: int = 0
    failed_by_status: dict[str, int] = field(default_factory=dict)

    def snapshot(self) -> CameraStatistics:
        return dataclasses.replace(self, failed_by_status=dict(self.failed_by_status))

    def as_dict(self) -> dict[str, object]:
        return dataclasses.asdict(self)


@runtime_checkable
class Camera(Protocol):
    """Every camera: see the module docstring for the life cycle and failure rules."""

    config: CameraConfig

    def open(self) -> None: ...
    def configure(self, config: CameraConfig) -> None: ...
    def start(self) -> None: ...
    def trigger(self) -> None: ...
    def grab(self, timeout_ms: int | None = None) -> Frame: ...
    def stop(self) -> None: ...
    def close(self) -> None: ...
    def statistics(self) -> CameraStatistics: ...
    def __enter__(self) -> Camera: ...
    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None: ...


class CameraBase:
    """Context manager and statistics plumbing shared by the implementations."""

    config: CameraConfig

    def __init__(self, config: CameraConfig) -> None:
        self.config = config
        self._stats = CameraStatistics()

    def statistics(self) -> CameraStatistics:
        return self._stats.snapshot()

    def open(self) -> None:  # pragma: no cover - overridden
        raise NotImplementedError

    def close(self) -> None:  # pragma: no cover - overridden
        raise NotImplementedError

    def __enter__(self) -> CameraBase:
        self.open()
        return self

    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> None:
        self.close()


def sensor_region(config: CameraConfig, sensor_w: int, sensor_h: int) -> tuple[int, int, int, int]:
    """(offset_x, offset_y, width, height) of ``config``'s region of interest on a ``sensor_w`` x ``sensor_h``
    sensor (0 = the rest of the sensor); ``CameraConfigError`` naming the keys when it does not fit on the sensor
    (some cameras, Aravis's fake among them, accept a region larger than their sensor and send garbage)."""
    w = config.width or sensor_w - config.offset_x
    h = config.height or sensor_h - config.offset_y
    for axis, offset, size, sensor in (("x", config.offset_x, w, sensor_w), ("y", config.offset_y, h, sensor_h)):
        name = "width" if axis == "x" else "height"
        if size <= 0 or offset + size > sensor:
            raise CameraConfigError(f"camera offset_{axis} + {name} = {offset} + {size} = {offset + size}: beyond the "
                                    f"sensor's {sensor} pixels ({sensor_w} x {sensor_h})")
    return config.offset_x, config.offset_y, w, h


class FrameIdTracker:
    """Unwraps camera frame ids into a monotonic counter and counts the frames lost in between.

    GigE Vision 1.x block ids are 16 bit, run 1..65535 and wrap to 1 (0 is never used); GigE Vision 2.x
    extended ids are 64 bit and do not wrap. The tracker switches to 64-bit mode once it sees an id > 65535.
    An id behind the newest one (less than half the 16-bit range back) is a late frame, not a wrap: with packet
    loss and resends, frames complete out of order. A late frame that was counted lost when its gap was seen is
    un-counted (lost = -1), so the net count never exceeds the ids actually skipped.
    After ``restart()`` (acquisition stopped and started) the next id is not compared with the last one, but the
    unwrapped counter keeps increasing.
    """

    WRAP = 65535
    REMEMBER_LOST = 4096
    """How many of the most recent ids counted lost are remembered, to un-count them when they arrive late."""

    def __init__(self) -> None:
        self._last_device: int | None = None
        self._unwrapped = 0
        self._wide = False
        self._lost: collections.OrderedDict[int, None] = collections.OrderedDict()  # unwrapped ids counted lost

    def restart(self) -> None:
        self._last_device = None
        self._lost.clear()

    @property
    def newest(self) -> int:
        """The newest unwrapped id so far (0 before the first frame); an id at or below it is late or repeated."""
        return self._unwrapped

    def update(self, device_id: int) -> tuple[int, int]:
        """(unwrapped id, frames lost since the previous id) for the next complete or failed frame. The count is
        -1 for a late frame that was counted lost before, 0 for a repeated id. Id 0 (never a camera's: Aravis's for
        a buffer whose leader was lost, so its id is unknown) changes nothing and comes back as repeated."""
        if device_id == 0:
            return self._unwrapped, 0
        if device_id > self.WRAP:
            self._wide = True
        if self._last_device is None:
            self._last_device = device_id
            self._unwrapped += 1
            return self._unwrapped, 0
        if self._wide:
            step = device_id - self._last_device
        else:
            step = ((device_id - 1) - (self._last_device - 1)) % self.WRAP
            if step > self.WRAP // 2:  # behind the newest id: late, not 32,000+ frames ahead
                step -= self.WRAP
        if step <= 0:  # a late (reordered) or repeated id: the counter stays where it is
            late = self._unwrapped + step
            if late in self._lost:
                del self._lost[late]
                return late, -1
            log.debug("frame id %d after %d: not increasing", device_id, self._last_device)
            return late, 0
        for missing in range(self._unwrapped + 1, self._unwrapped + min(step, self.REMEMBER_LOST + 1)):
            self._lost[missing] = None
        while len(self._lost) > self.REMEMBER_LOST:
            self._lost.popitem(last=False)
        self._last_device = device_id
        self._unwrapped += step
        return self._unwrapped, step - 1


def backoff_delays_s(initial_s: float, max_s: float, attempts: int) -> Iterator[float]:
    """Waits before each reconnect attempt: ``initial_s`` doubled each time, capped at ``max_s``."""
    delay = initial_s
    for _ in range(attempts):
        yield delay
        delay = min(delay * 2, max_s)
