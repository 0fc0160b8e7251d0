"""GenICam cameras through Aravis 0.8 (PyGObject): GigE Vision and USB3 Vision, behind ``drivers.camera.Camera``.

Opening (and the network rule: GigE Vision discovery broadcasts on every interface):
    - ``device`` is an IPv4 address: the camera is opened by unicast (``Aravis.GvDevice.new``), with no discovery
      at all. This is the way to use a GigE camera.
    - ``device`` is a device id, serial number or "": the device list is searched. GigE Vision discovery is part of
      that search only when ``gige_discovery=True`` is passed (``station cameras --gige-discovery``); otherwise the
      GigE Vision interface is disabled and only USB3 Vision (and GenTL) devices are found.

Streaming: a pool of ``config.n_buffers`` buffers. ``grab`` pops buffers until a SUCCESS one arrives; every popped
buffer is pushed back (else the pool starves); incomplete buffers are counted by status and logged. The image
bytes are copied once out of the buffer (``get_image_data``) and decoded without a further copy for Mono8/Mono16.

Loss: a grab that times out (or a failed command) probes the device with one register read. If that fails (the
GVCP timeout is ~2.5 s) or the heartbeat thread reported ``control-lost``, the camera is lost: with
``config.reconnect`` it is reopened with back-off and the stream restarted, else ``CameraLost`` is raised.
Statistics survive both. A lost device's objects are dropped in a worker thread (their finalisers wait for GVCP
timeouts), with the driver's ``control-lost`` handler disconnected first: GLib then skips the signal, so the lost
device's heartbeat thread, which emits it when a camera answers at that address again, never holds a reference to the
device. Had it held the last one, the device would be finalised on that thread, which joins itself (a GLib error: the
process dies of SIGTRAP); and the old device's signal would mark the new connection lost.

Aravis objects are dropped in ``close()`` (also at interpreter exit): a stream still alive at exit aborts the
process in ``g_mutex_clear``.
"""

from __future__ import annotations

import atexit
import functools
import ipaddress
import logging
import socket
import threading
import time
import weakref
from dataclasses import dataclass
from typing import Any

from drivers import pixel_formats
from drivers.camera import CameraBase, CameraConfig, FrameIdTracker, backoff_delays_s, sensor_region
from drivers.errors import (
    CameraConfigError,
    CameraError,
    CameraLost,
    CameraNotFound,
    CameraTimeout,
    PixelFormatError,
    TriggerFailed,
)
from drivers.frame import Frame

log = logging.getLogger(__name__)

NEUTRAL_FEATURES: tuple[tuple[str, int | bool], ...] = (
    ("DecimationHorizontal", 1), ("DecimationVertical", 1), ("ReverseX", False), ("ReverseY", False))
"""GenICam features set to these values where a camera has them (besides binning 1x1): each would change which
polarizer angle a pixel of the mosaic holds."""

GAMMA_TOLERANCE = 1e-3
"""A ``Gamma`` within this of 1 is linear (what a camera reads back may differ from 1 in its last digits)."""

GVCP_PORT = 3956
_OPEN: weakref.WeakSet[AravisCamera] = weakref.WeakSet()


@functools.cache
def _aravis() -> tuple[Any, Any, Any]:
    """(Aravis, GLib, Gio), imported on first use so ``drivers`` imports without PyGObject."""
    import gi

    gi.require_version("Aravis", "0.8")
    from gi.repository import Aravis, Gio, GLib

    return Aravis, GLib, Gio


def is_ip_address(device: str) -> bool:
    try:
        ipaddress.IPv4Address(device)
    except ValueError:
        return False
    return True


def local_address_for(device_ip: str) -> str:
    """The host's address on the route to ``device_ip`` (a UDP ``connect`` sends nothing)."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.connect((device_ip, GVCP_PORT))
        return s.getsockname()[0]


def _set_gige_discovery(enabled: bool) -> None:
    Aravis, _, _ = _aravis()
    (Aravis.enable_interface if enabled else Aravis.disable_interface)("GigEVision")


@dataclass(frozen=True)
class CameraInfo:
    device_id: str
    vendor: str
    model: str
    serial: str
    address: str
    protocol: str


def list_cameras(*, gige_discovery: bool = False, addresses: tuple[str, ...] = ()) -> list[CameraInfo]:
    """Cameras found on USB3 Vision (always), by GigE Vision broadcast discovery (only if ``gige_discovery``), and
    at each of ``addresses`` by unicast. An address that does not answer is a ``CameraNotFound``."""
    Aravis, GLib, _ = _aravis()
    _set_gige_discovery(gige_discovery)
    Aravis.update_device_list()
    found = [CameraInfo(Aravis.get_device_id(i) or "", Aravis.get_device_vendor(i) or "",
                        Aravis.get_device_model(i) or "", Aravis.get_device_serial_nbr(i) or "",
                        Aravis.get_device_address(i) or "", Aravis.get_device_protocol(i) or "")
             for i in range(Aravis.get_n_devices())]
    for addr in addresses:
        if any(c.address == addr for c in found):
            continue
        cam = Aravis.Camera.new_with_device(_open_gv_device(addr))
        try:
            vendor, model = cam.get_vendor_name() or "", cam.get_model_name() or ""
            serial, device_id = cam.get_device_serial_number() or "", cam.get_device_id() or ""
        except GLib.Error as exc:
            raise CameraError(f"camera at {addr}: cannot read its identity: {exc.message}") from None
        found.append(CameraInfo(f"{vendor}-{model}-{serial}" if serial else device_id, vendor, model,
                                serial or device_id, addr, "GigEVision"))
    return found


def _open_gv_device(address: str) -> Any:
    ip = ipaddress.IPv4Address(address)
    if ip.is_multicast or ip.is_unspecified or ip == ipaddress.IPv4Address("255.255.255.255"):
        raise CameraConfigError(f"camera at {address}: not a single camera's address (broadcast, multicast or "
                                "unspecified: that is discovery, which needs --gige-discovery)")
    Aravis, GLib, Gio = _aravis()
    try:
        local = local_address_for(address)
    except OSError as exc:
        raise CameraNotFound(f"camera at {address}: no route to it ({exc})") from None
    try:
        return Aravis.GvDevice.new(Gio.InetAddress.new_from_string(local), Gio.InetAddress.new_from_string(address))
    except GLib.Error as exc:
        raise CameraNotFound(f"camera at {address}: no GigE Vision device answers ({exc.message})") from None


class AravisCamera(CameraBase):
    """A GenICam camera through Aravis; see the module docstring and ``drivers.camera`` for the rules."""

    def __init__(self, config: CameraConfig, *, gige_discovery: bool = False) -> None:
        super().__init__(config)
        self.gige_discovery = gige_discovery
        self._camera: Any = None
        self._stream: Any = None
        self._started = False
        self._lost = threading.Event()
        self._control_lost_handler = 0  # the id of the handler on the open device's control-lost signal
        self._tracker = FrameIdTracker()
        self._format: pixel_formats.PixelFormat | None = None
        self._stream_base = {"resent": 0, "missing_packets": 0}  # counters of streams already torn down
        self._lock = threading.RLock()

    # -- life cycle ---------------------------------------------------------------------------------------------
    def open(self) -> None:
        with self._lock:
            if self._camera is not None:
                return
            try:
                self._connect()
                self._apply(self.config)
            except BaseException:
                self.close()
                raise
            _OPEN.add(self)

    def configure(self, config: CameraConfig) -> None:
        with self._lock:
            if self._started:
                raise CameraError(f"camera {self.name}: configure while streaming; stop() first")
            if self._camera is not None:
                self._apply(config)
            self.config = config

    def start(self) -> None:
        with self._lock:
            if self._camera is None:
                raise CameraError(f"camera {self.config.device or '(any)'}: start before open")
            if not self._started:
                self._start_stream()

    def trigger(self) -> None:
        if self.config.trigger != "software":
            raise CameraError(f"camera {self.name}: trigger() needs trigger = 'software', not {self.config.trigger!r}")
        if not self._started:
            raise CameraError(f"camera {self.name}: trigger before start")
        _, GLib, _ = _aravis()
        try:
            self._camera.software_trigger()
        except GLib.Error as exc:
            self._handle_loss(f"software trigger failed: {exc.message}")
            try:
                self._camera.software_trigger()
            except GLib.Error as again:
                raise TriggerFailed(f"camera {self.name}: software trigger failed after a reconnect: "
                                    f"{again.message}") from None

    def stop(self) -> None:
        with self._lock:
            if not self._started:
                return
            self._started = False
            self._teardown_stream(stop_acquisition=True)

    def close(self) -> None:
        with self._lock:
            self.stop()
            self._teardown_stream(stop_acquisition=False)
            self._drop_camera()
            _OPEN.discard(self)

    @property
    def name(self) -> str:
        return self.config.device or "(only camera)"

    # -- grabbing -----------------------------------------------------------------------------------------------
    def grab(self, timeout_ms: int | None = None) -> Frame:
        if not self._started:
            raise CameraError(f"camera {self.name}: grab before start")
        _, GLib, _ = _aravis()
        timeout_s = (timeout_ms if timeout_ms is not None else self.config.timeout_ms) / 1e3
        deadline = time.monotonic() + timeout_s
        while True:
            remaining_us = int((deadline - time.monotonic()) * 1e6)
            buf = self._stream.timeout_pop_buffer(remaining_us) if remaining_us > 0 else None
            if buf is None:
                if self._lost.is_set() or not self._alive():
                    self._handle_loss("no frame and the device does not answer")
                    deadline = time.monotonic() + timeout_s  # reconnected: wait for a frame again
                    continue
                self._stats.timeouts += 1
                raise CameraTimeout(f"camera {self.name}: no complete frame within {timeout_s * 1e3:.0f} ms "
                                    f"(trigger {self.config.trigger})")
            try:
                frame = self._frame_from(buf, GLib)
            finally:
                self._stream.push_buffer(buf)
            if frame is not None:
                self._stats.completed += 1
                return frame

    def _frame_from(self, buf: Any, GLib: Any) -> Frame | None:
        Aravis, _, _ = _aravis()
        status = buf.get_status()
        device_id = buf.get_frame_id()
        newest = self._tracker.newest
        frame_id, lost = self._tracker.update(device_id)
        self._stats.dropped += lost  # -1: a frame counted lost arrived late (it is counted below instead)
        if lost > 0:
            log.warning("camera %s: %d frame(s) lost before frame id %d", self.name, lost, device_id)
        late = frame_id <= newest
        if late and lost == 0:  # a second buffer for a frame id already counted: nothing new to count
            log.debug("camera %s: frame id %d again: not delivered", self.name, device_id)
            return None
        if status != Aravis.BufferStatus.SUCCESS or late:
            # a late frame is never delivered: in free run its frame number was already logged as lost, and with
            # a trigger it belongs to an earlier part than the one now waiting for a frame
            nick = "late" if status == Aravis.BufferStatus.SUCCESS else status.value_nick
            self._stats.failed += 1
            self._stats.failed_by_status[nick] = self._stats.failed_by_status.get(nick, 0) + 1
            log.warning("camera %s: frame id %d %s: not delivered", self.name, device_id,
                        "arrived out of order" if nick == "late" else f"incomplete ({nick})")
            return None
        width, height = buf.get_image_width(), buf.get_image_height()
        pf = self._format
        code = buf.get_image_pixel_format()
        if pf is None or (pf.code is not None and pf.code != code):
            pf = pixel_formats.lookup(code)
        x_pad, _ = buf.get_image_padding()
        stride = pf.payload_bytes(width, 1) + x_pad if x_pad else None
        raw, bits = pixel_formats.decode(buf.get_image_data(), width, height, pf, row_stride_bytes=stride)
        return Frame(raw=raw, pixel_format=pf.name, bit_depth=bits, frame_id=frame_id,
                     timestamp_ns=int(buf.get_timestamp()), host_timestamp_ns=int(buf.get_system_timestamp()),
                     device_frame_id=int(device_id))

    def statistics(self):  # type: ignore[override]
        with self._lock:
            self._refresh_stream_stats()
            return self._stats.snapshot()

    # -- internals ----------------------------------------------------------------------------------------------
    def _connect(self) -> None:
        Aravis, GLib, _ = _aravis()
        device = self.config.device
        if is_ip_address(device):
            self._camera = Aravis.Camera.new_with_device(_open_gv_device(device))
        else:
            _set_gige_discovery(self.gige_discovery)
            Aravis.update_device_list()
            ids = [(Aravis.get_device_id(i), Aravis.get_device_serial_nbr(i), Aravis.get_device_address(i))
                   for i in range(Aravis.get_n_devices())]
            matches = [i for i in ids if not device or device in i]
            where = "USB3 Vision" + (" and GigE Vision discovery" if self.gige_discovery else
                                     " (GigE Vision discovery off: give the camera's IP address)")
            if not matches:
                raise CameraNotFound(f"camera {device or '(any)'}: not found on {where}; found: "
                                     f"{', '.join(i[0] for i in ids) or 'none'}")
            if len(matches) > 1:
                raise CameraError(f"camera {device or '(any)'}: {len(matches)} cameras match "
                                  f"({', '.join(m[0] for m in matches)}); set camera.device")
            try:
                self._camera = Aravis.Camera.new(matches[0][0])
            except GLib.Error as exc:
                raise CameraNotFound(f"camera {matches[0][0]}: cannot open: {exc.message}") from None
        self._lost.clear()
        self._control_lost_handler = self._camera.get_device().connect("control-lost", lambda _dev: self._lost.set())
        log.info("camera %s: opened %s %s (serial %s)", self.name, self._camera.get_vendor_name(),
                 self._camera.get_model_name(), self._camera.get_device_serial_number())

    def _apply(self, cfg: CameraConfig) -> None:
        """Push ``cfg`` to the camera (stopped); errors name the feature and value."""
        Aravis, GLib, _ = _aravis()
        cam = self._camera

        def step(feature: str, value: object, fn: Any, *args: Any) -> None:
            try:
                fn(*args)
            except GLib.Error as exc:
                raise CameraConfigError(f"camera {self.name}: {feature} = {value}: {exc.message}") from None

        available = cam.dup_available_pixel_formats_as_strings() or []
        if cfg.pixel_format not in available:
            raise CameraConfigError(f"camera {self.name}: pixel_format {cfg.pixel_format!r} not offered; "
                                    f"the camera has {', '.join(available)}")
        step("pixel_format", cfg.pixel_format, cam.set_pixel_format_from_string, cfg.pixel_format)
        code = cam.get_pixel_format()
        try:
            self._format = pixel_formats.lookup(code)
        except PixelFormatError:
            try:  # vendor formats known by name only (FLIR Polarized*)
                self._format = pixel_formats.lookup(cfg.pixel_format)
            except PixelFormatError as exc:
                raise CameraConfigError(f"camera {self.name}: pixel_format {cfg.pixel_format!r}: {exc}") from None
        # the polarizer mosaic only survives whole: undo binning, decimation and mirroring another tool left set
        if cam.is_binning_available():
            step("binning", "1x1", cam.set_binning, 1, 1)
            if tuple(cam.get_binning()) != (1, 1):
                raise CameraConfigError(f"camera {self.name}: binning stays {tuple(cam.get_binning())}; the "
                                        "polarizer mosaic needs 1x1")
        for feature, value in NEUTRAL_FEATURES:
            if cam.is_feature_available(feature):
                setter = cam.set_boolean if isinstance(value, bool) else cam.set_integer
                step(feature, value, setter, feature, value)
        self._make_linear()
        sensor_w, sensor_h = cam.get_sensor_size()
        _, _, w, h = sensor_region(cfg, sensor_w, sensor_h)
        step("region", (cfg.offset_x, cfg.offset_y, w, h), cam.set_region, cfg.offset_x, cfg.offset_y, w, h)
        got = tuple(cam.get_region())
        if got != (cfg.offset_x, cfg.offset_y, w, h):
            raise CameraConfigError(f"camera {self.name}: region (x, y, w, h) = {(cfg.offset_x, cfg.offset_y, w, h)} "
                                    f"was adjusted to {got} by the camera: choose values on its increments")
        if cam.is_exposure_time_available():
            if cam.is_exposure_auto_available():
                step("exposure_auto", "Off", cam.set_exposure_time_auto, Aravis.Auto.OFF)
            self._bounded(cfg.exposure_us, cam.get_exposure_time_bounds(), "exposure_us")
            step("exposure_us", cfg.exposure_us, cam.set_exposure_time, cfg.exposure_us)
        if cam.is_gain_available():
            if cam.is_gain_auto_available():
                step("gain_auto", "Off", cam.set_gain_auto, Aravis.Auto.OFF)
            self._bounded(cfg.gain_db, cam.get_gain_bounds(), "gain_db")
            step("gain_db", cfg.gain_db, cam.set_gain, cfg.gain_db)
        step("acquisition_mode", "Continuous", cam.set_acquisition_mode, Aravis.AcquisitionMode.CONTINUOUS)
        if cam.is_frame_rate_available():
            self._bounded(cfg.frame_rate_hz, cam.get_frame_rate_bounds(), "frame_rate_hz")
            step("frame_rate_hz", cfg.frame_rate_hz, cam.set_frame_rate, cfg.frame_rate_hz)
        if cfg.trigger == "free_run":
            step("trigger", "free_run", cam.clear_triggers)
        else:
            source = "Software" if cfg.trigger == "software" else f"Line{cfg.trigger[4:]}"
            sources = cam.dup_available_trigger_sources() or []
            if source not in sources:
                raise CameraConfigError(f"camera {self.name}: trigger {cfg.trigger!r} (source {source}) not offered; "
                                        f"the camera has {', '.join(sources) or 'no trigger'}")
            step("trigger", cfg.trigger, cam.set_trigger, source)
        if cam.is_gv_device():
            if cfg.packet_size:
                step("packet_size", cfg.packet_size, cam.gv_set_packet_size, cfg.packet_size)
            else:
                step("packet_size", "auto", cam.gv_auto_packet_size)
            log.info("camera %s: GigE Vision packet size %d B", self.name, cam.gv_get_packet_size())

    def _make_linear(self) -> None:
        """Turn the camera's tone curve off: the model reads linear codes, and a look-up table or a gamma another
        tool left on bends them (a gamma of 0.8 cost the shipped file 5 points; docs/results/2026-12-04-gamma.md).
        ``LUTEnable`` off; ``GammaEnable`` off where the camera has it, else (or if it stays on) ``Gamma`` 1. Each
        change is logged and read back; a curve that stays on is a ``CameraConfigError`` naming the feature.
        Features a camera lacks are skipped (a camera with none is taken as linear); a ``Gamma`` that is not a float
        (an enumeration of curves on some cameras) cannot be read as linear or not: a warning, and the drift
        monitor's level warnings are left to catch a curve."""
        Aravis, GLib, _ = _aravis()
        cam = self._camera
        has = cam.is_feature_available

        def set_off(feature: str) -> bool:
            """True when ``feature`` was on and is now off (False: stays on, or the write was refused)."""
            log.warning("camera %s: %s was on (another tool left it); turning it off: the model reads linear "
                        "codes", self.name, feature)
            try:
                cam.set_boolean(feature, False)
            except GLib.Error as exc:
                log.warning("camera %s: %s = off refused: %s", self.name, feature, exc.message)
                return False
            return not cam.get_boolean(feature)

        def gamma() -> float:
            return float(cam.get_float("Gamma")) if has("Gamma") else 1.0

        def refuse(what: str, fix: str) -> None:
            raise CameraConfigError(f"camera {self.name}: {what}: the model reads linear codes; {fix} (in the "
                                    "camera's user set or with its vendor's tool)")

        try:
            if has("LUTEnable") and cam.get_boolean("LUTEnable") and not set_off("LUTEnable"):
                refuse("LUTEnable stays on", "set LUTEnable off")
            node = cam.get_device().get_feature("Gamma") if has("Gamma") else None
            readable = node is None or isinstance(node, Aravis.GcFloat)
            if readable and abs(gamma() - 1.0) <= GAMMA_TOLERANCE:
                return
            enable = has("GammaEnable")
            if enable and (not cam.get_boolean("GammaEnable") or set_off("GammaEnable")):
                return
            if not readable:
                log.warning("camera %s: its Gamma is not a number (%s): the station cannot tell whether the camera "
                            "runs linear; set it linear by hand (the drift monitor warns of a tone curve)", self.name,
                            type(node).__name__)
                return
            log.warning("camera %s: Gamma was %g (another tool left it); setting 1: the model reads linear codes",
                        self.name, gamma())
            try:
                cam.set_float("Gamma", 1.0)
            except GLib.Error as exc:
                log.warning("camera %s: Gamma = 1 refused: %s", self.name, exc.message)
            if abs(gamma() - 1.0) > GAMMA_TOLERANCE:
                refuse(("GammaEnable stays on and " if enable else "") + f"Gamma stays {gamma():g}",
                       "set GammaEnable off or Gamma 1" if enable else "set Gamma 1")
        except GLib.Error as exc:
            raise CameraConfigError(f"camera {self.name}: cannot read its tone features (LUTEnable, GammaEnable, "
                                    f"Gamma): {exc.message}") from None

    def _bounded(self, value: float, bounds: Any, key: str) -> None:
        lo, hi = bounds
        if not lo <= value <= hi:
            raise CameraConfigError(f"camera {self.name}: {key} = {value} outside the camera's range [{lo}, {hi}]")

    def _start_stream(self) -> None:
        Aravis, GLib, _ = _aravis()
        try:
            self._stream = self._camera.create_stream(None, None)
            payload = self._camera.get_payload()  # re-read: it changes with every configuration
            for _ in range(self.config.n_buffers):
                self._stream.push_buffer(Aravis.Buffer.new_allocate(payload))
            self._camera.start_acquisition()
        except GLib.Error as exc:
            self._teardown_stream(stop_acquisition=False)
            raise CameraError(f"camera {self.name}: cannot start streaming: {exc.message}") from None
        self._tracker.restart()
        self._started = True

    def _teardown_stream(self, *, stop_acquisition: bool, release: list[Any] | None = None) -> None:
        """Stop and drop the stream. With ``release`` (a lost camera) the stream is appended to it instead of
        being finalised here: finalising objects of a dead device waits for GVCP timeouts (~5 s each)."""
        _, GLib, _ = _aravis()
        if stop_acquisition and self._camera is not None and not self._lost.is_set():
            try:
                self._camera.stop_acquisition()
            except GLib.Error as exc:
                log.warning("camera %s: stop acquisition failed (%s)", self.name, exc.message)
        if self._stream is not None:
            self._refresh_stream_stats()
            base = self._stream_stats_now()
            for k, v in base.items():
                self._stream_base[k] += v
            if release is not None:
                release.append(self._stream)
            self._stream = None  # the last reference (unless released): the stream thread ends here

    def _stream_stats_now(self) -> dict[str, int]:
        s = self._stream
        if s is None or not hasattr(s, "get_info_uint64_by_name"):
            return {"resent": 0, "missing_packets": 0}
        try:
            return {"resent": int(s.get_info_uint64_by_name("n_resent_packets")),
                    "missing_packets": int(s.get_info_uint64_by_name("n_missing_packets"))}
        except Exception:  # USB3 streams have no packet counters
            return {"resent": 0, "missing_packets": 0}

    def _refresh_stream_stats(self) -> None:
        now = self._stream_stats_now()
        self._stats.resent = self._stream_base["resent"] + now["resent"]
        self._stats.missing_packets = self._stream_base["missing_packets"] + now["missing_packets"]

    def _alive(self) -> bool:
        _, GLib, _ = _aravis()
        try:
            if self._camera.is_gv_device():
                self._camera.get_device().read_register(0x0000)  # GigE Vision bootstrap: Version
            else:
                self._camera.get_integer("Width")
        except GLib.Error:
            return False
        return True

    def _drop_camera(self) -> Any:
        """Disconnect the control-lost handler from the device and forget the camera; returns it (or None) for the
        caller to release. See the module docstring: no handler may be left on a device being dropped."""
        cam, self._camera = self._camera, None
        if cam is not None and self._control_lost_handler:
            device = cam.get_device()
            if device.handler_is_connected(self._control_lost_handler):
                device.disconnect(self._control_lost_handler)
        self._control_lost_handler = 0
        return cam

    def _handle_loss(self, why: str) -> None:
        """Reconnect with back-off (if configured) or raise ``CameraLost``; statistics are kept either way."""
        stats = self.statistics()
        log.error("camera %s: lost (%s); completed %d, failed %d, dropped %d", self.name, why, stats.completed,
                  stats.failed, stats.dropped)
        was_started = self._started
        self._started = False
        self._lost.set()
        dead: list[Any] = []
        self._teardown_stream(stop_acquisition=False, release=dead)
        dead.append(self._drop_camera())
        _release_in_background(dead)
        if self.config.reconnect:
            for attempt, delay_s in enumerate(backoff_delays_s(self.config.reconnect_backoff_s,
                                                               self.config.reconnect_backoff_max_s,
                                                               self.config.reconnect_attempts), 1):
                time.sleep(delay_s)
                try:
                    self._connect()
                    self._apply(self.config)
                    if was_started:
                        self._start_stream()
                except CameraError as exc:
                    log.warning("camera %s: reconnect attempt %d/%d failed: %s", self.name, attempt,
                                self.config.reconnect_attempts, exc)
                    if (half_open := self._drop_camera()) is not None:  # opened, then refused its settings
                        _release_in_background([half_open])
                    continue
                self._stats.reconnects += 1
                log.info("camera %s: reconnected after %d attempt(s)", self.name, attempt)
                return
        raise CameraLost(f"camera {self.name}: lost ({why})"
                         + (f"; {self.config.reconnect_attempts} reconnect attempts failed" if self.config.reconnect
                            else "; reconnect is off")
                         + f". Frames: {stats.completed} completed, {stats.failed} incomplete, {stats.dropped} dropped")


RELEASE_DELAY_S = 1.0
"""How long a lost device's objects are kept before they are dropped: a control-lost emission under way when its
handler was disconnected (it holds a reference to the device until it ends, microseconds later) has ended by then."""


def _release_in_background(objects: list[Any]) -> None:
    """Drop the last references to a lost device's Aravis objects in a worker thread (their finalisers wait for
    GVCP timeouts), ``RELEASE_DELAY_S`` later. The thread is not a daemon: the interpreter waits for it, so no stream
    outlives exit."""
    def release() -> None:
        time.sleep(RELEASE_DELAY_S)
        objects.clear()

    threading.Thread(target=release, name="aravis-release", daemon=False).start()


@atexit.register
def _close_all() -> None:
    for cam in list(_OPEN):
        cam.close()
