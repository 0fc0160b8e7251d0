"""The virtual polarization camera served as a real GigE Vision device from this process.

Aravis's fake GigE Vision camera (``ArvGvFakeCamera``, the device behind ``arv-fake-gv-camera-0.8``) answers
GVCP and streams GVSP on one interface; its image callback is replaced so that every frame it sends is the next
raw mosaic of a ``VirtualCamera`` (same draw: random part, defective with probability ``defect_rate``). Any
GigE Vision client, ``AravisCamera`` included, opens it by address.

Everything goes through ctypes on ``libaravis-0.8.so.0``, not PyGObject: the fill-pattern hook
(``arv_fake_camera_set_fill_pattern``) segfaults through gi once frames start (its callback is ``scope call``),
and a ctypes call releases the GIL, so ``close()`` can wait for the camera's thread while that thread finishes
a callback that needs the GIL.

What the device offers (its GenICam XML is Aravis's fake-camera XML with the PixelFormat list cut to one entry):
    size          SensorWidth x SensorHeight = the dataset's frame size; Width/Height/OffsetX/OffsetY select a
                  region of the mosaic (keep offsets even: whole 2x2 polarizer superpixels).
    pixel format  one, from the dataset's bit depth: Mono8, Mono10, Mono12, Mono14 or Mono16 (unpacked 16-bit
                  little-endian words for 10-16 bits, so the receiver decodes the right full scale).
    trigger       free run at AcquisitionFrameRate, or TriggerMode On + TriggerSource Software (one frame per
                  TriggerSoftware; the device checks for a trigger ``trigger_poll_hz`` times a second).
    frame sets    a set with a frame per dome segment (``station render --dome-segments``) is served part by part,
                  its frames in the segments' order, one per frame sent: the station, with ``[camera]
                  dome_segments`` and a software trigger, triggers each. A trigger the device never sees shifts
                  every later set by a frame (a real line's light sequencer, reset by the PLC per part, does not):
                  the station then rejects those parts, whose frames disagree.
    tone          Gamma (float), GammaEnable and LUTEnable, the features a real camera bends its codes with; linear
                  and writable unless ``tone`` (a ``ServedTone``) says how another tool left them. While on, the
                  served codes are full (code / full)^Gamma, then, with LUTEnable, full (code / full)^0.5 (the
                  served look-up table is fixed). A rehearsal of the driver's tone check (``AravisCamera``).
    ignored       ExposureTime and Gain (the frames are rendered), binning.
    frame ids     16-bit GigE Vision block ids, wrapping 65535 -> 1; timestamps in nanoseconds since
                  1970 (host clock at microsecond resolution), carried in the GVSP leader.

Ground truth cannot travel over GigE Vision. Each served frame is recorded as a ``ServedFrame`` (frame id and
device timestamp -> sample index, label, split, defect type), kept in memory (``recent``) and, with
``truth_path``, appended as one JSON line per frame. The receiver's ``Frame.timestamp_ns`` (the inspection log's
``camera_timestamp_ns``) is the device timestamp, unique per frame: join on it (``read_truth``).

Network rule (nothing may leave loopback): only a loopback interface is allowed unless ``allow_network=True``.
Aravis's device also binds the discovery port on 255.255.255.255 and answers discovery broadcasts arriving on any
interface (checked in a namespace: a broadcast sent from a second interface got an answer). On loopback this
process therefore holds that port itself first (``_discovery_guard``): the device's bind fails and it is reachable
by unicast to its address only (``AravisCamera`` opens it so; GigE discovery does not list it).
"""

from __future__ import annotations

import atexit
import collections
import ctypes
import errno
import fcntl
import functools
import ipaddress
import json
import logging
import os
import re
import socket
import struct
import tempfile
import threading
import weakref
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import IO, Any

import numpy as np

from drivers import pixel_formats
from drivers.aravis_camera import GVCP_PORT
from drivers.camera import CameraConfig
from drivers.errors import CameraConfigError, CameraError
from drivers.netns import in_private_netns
from drivers.virtual_camera import VirtualCamera, VirtualCameraConfig

log = logging.getLogger(__name__)

FORMAT_BY_BIT_DEPTH = {8: "Mono8", 10: "Mono10", 12: "Mono12", 14: "Mono14", 16: "Mono16"}
"""The wire format served for a dataset of each bit depth."""

# Register addresses of Aravis 0.8's fake camera (arvfakecamera.h) and GigE Vision bootstrap registers.
_REG_WIDTH, _REG_HEIGHT, _REG_PIXEL_FORMAT = 0x100, 0x104, 0x128
_REG_SENSOR_WIDTH, _REG_SENSOR_HEIGHT = 0x11C, 0x118
_GVBS_CURRENT_IP, _GVBS_MANUFACTURER, _GVBS_MODEL, _GVBS_INFO = 0x24, 0x48, 0x68, 0xA8
_REG_GAMMA, _REG_GAMMA_ENABLE, _REG_LUT_ENABLE, _REG_GAMMA_INTEGER = 0x400, 0x404, 0x408, 0x40C  # free registers
LUT_GAMMA = 0.5
"""The exponent of the served camera's fixed look-up table."""
GAMMA_RANGE = (0.25, 4.0)
"""The served ``Gamma`` feature's bounds (its GenICam Min and Max, and ``ServedTone.gamma``'s)."""
_SERIAL_MAX = 15  # bootstrap SerialNumber is 16 bytes with the terminating NUL
_IFF_LOOPBACK = 0x8
_SIOCGIFFLAGS, _SIOCGIFADDR = 0x8913, 0x8915

_FillPattern = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_uint32, ctypes.c_uint32,
                                ctypes.c_uint32)
"""``ArvFakeCameraFillPattern``: (buffer, user data, exposure_time_us, gain, pixel_format)."""

_OPEN: weakref.WeakSet[GvCameraServer] = weakref.WeakSet()


@functools.cache
def _lib() -> ctypes.CDLL:
    """libaravis with the prototypes used here (loaded once; the same library PyGObject loads)."""
    try:
        lib = ctypes.CDLL("libaravis-0.8.so.0")
    except OSError as exc:
        raise CameraError(f"GigE Vision server: libaravis-0.8.so.0 not found ({exc}); install the Debian package "
                          "libaravis-0.8-0") from None
    vp, u32, i32 = ctypes.c_void_p, ctypes.c_uint32, ctypes.c_int
    protos: dict[str, tuple[Any, list[Any]]] = {
        "arv_gv_fake_camera_new_full": (vp, [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p]),
        "arv_gv_fake_camera_is_running": (i32, [vp]),
        "arv_gv_fake_camera_get_fake_camera": (vp, [vp]),
        "arv_fake_camera_new": (vp, [ctypes.c_char_p]),
        "arv_fake_camera_get_genicam_xml": (ctypes.c_char_p, [vp, ctypes.POINTER(ctypes.c_size_t)]),
        "arv_fake_camera_write_register": (i32, [vp, u32, u32]),
        "arv_fake_camera_read_register": (i32, [vp, u32, ctypes.POINTER(u32)]),
        "arv_fake_camera_write_memory": (i32, [vp, u32, u32, ctypes.c_char_p]),
        "arv_fake_camera_set_trigger_frequency": (None, [vp, ctypes.c_double]),
        "arv_fake_camera_set_fill_pattern": (None, [vp, _FillPattern, vp]),
        "arv_buffer_get_data": (vp, [vp, ctypes.POINTER(ctypes.c_size_t)]),
        "arv_buffer_get_image_width": (i32, [vp]),
        "arv_buffer_get_image_height": (i32, [vp]),
        "arv_buffer_get_image_x": (i32, [vp]),
        "arv_buffer_get_image_y": (i32, [vp]),
        "arv_buffer_get_frame_id": (ctypes.c_uint64, [vp]),
        "arv_buffer_get_timestamp": (ctypes.c_uint64, [vp]),
        "g_object_unref": (None, [vp]),  # exported by libgobject, a dependency of libaravis
    }
    for name, (restype, argtypes) in protos.items():
        fn = getattr(lib, name)
        fn.restype, fn.argtypes = restype, argtypes
    return lib


def _ifreq(interface: str, request: int) -> bytes:
    """``ioctl(request)`` on a ``struct ifreq`` naming ``interface`` (this network namespace's view, unlike
    /sys/class/net, which shows the namespace sysfs was mounted in)."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        return fcntl.ioctl(s.fileno(), request, struct.pack("256s", interface.encode()[:15]))


def is_loopback_interface(interface: str) -> bool:
    """Whether ``interface`` (a name such as "lo", or an IPv4 address) is a loopback interface.

    An unknown name is a ``CameraConfigError``."""
    try:
        return ipaddress.IPv4Address(interface).is_loopback
    except ValueError:
        pass
    try:
        flags = struct.unpack_from("H", _ifreq(interface, _SIOCGIFFLAGS), 16)[0]
    except OSError:
        names = ", ".join(sorted(name for _, name in socket.if_nameindex()))
        raise CameraConfigError(f"GigE Vision server: no network interface {interface!r} (have {names})") from None
    return bool(flags & _IFF_LOOPBACK)


def interface_address(interface: str) -> str:
    """The IPv4 address the device will answer at: ``interface`` itself when it is an address, else the named
    interface's address (``CameraConfigError`` when it has none)."""
    try:
        return str(ipaddress.IPv4Address(interface))
    except ValueError:
        pass
    is_loopback_interface(interface)  # an unknown name: the error lists the interfaces
    try:
        return socket.inet_ntoa(_ifreq(interface, _SIOCGIFADDR)[20:24])
    except OSError:
        raise CameraConfigError(f"GigE Vision server: interface {interface!r} has no IPv4 address") from None


def _check_gvcp_port_free(address: str) -> None:
    """Raise when the GVCP port cannot be bound at ``address`` (Aravis's device would then start without
    listening and say nothing)."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        try:
            s.bind((address, GVCP_PORT))
        except OSError as exc:
            why = ("taken by another GigE Vision device (arv-fake-gv-camera, another serve-camera)"
                   if exc.errno == errno.EADDRINUSE else exc.strerror)
            raise CameraError(f"GigE Vision server: cannot listen on {address}:{GVCP_PORT}: {why}") from None


@functools.cache
def _discovery_guard() -> socket.socket | None:
    """This process's socket on 255.255.255.255:3956, bound without SO_REUSEADDR so that the device's own
    discovery socket (bound with it) fails: broadcasts from a network then reach a socket that never answers.
    Held until the process exits; None when another process holds the port."""
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    try:
        s.bind(("255.255.255.255", GVCP_PORT))
    except OSError:
        s.close()
        return None
    return s


@dataclass(frozen=True)
class ServedFrame:
    """Ground truth of one served frame.

    frame_id      GigE Vision block id as sent (16 bit: 1..65535, wraps to 1) = the receiver's ``device_frame_id``.
    timestamp_ns  device timestamp, ns since 1970 = the receiver's ``Frame.timestamp_ns``; unique per frame.
    sample_index  the dataset sample shown; label 1 defective / 0 good; split and defect type as in ``params.json``.
    present       False when the frame shows no part (an empty scene; label 0).
    """

    frame_id: int
    timestamp_ns: int
    sample_index: int
    label: int
    split: str | None
    defect_type: str | None
    present: bool = True


@dataclass(frozen=True)
class ServedTone:
    """The served camera's tone features as another tool (a vendor viewer, a saved user set) left them.

    gamma         the ``Gamma`` feature; served codes are full (code / full)^gamma while it applies.
    gamma_enable  the ``GammaEnable`` feature; None: the camera has none and its Gamma always applies.
    lut_enable    the ``LUTEnable`` feature: codes then pass the fixed table full (code / full)^``LUT_GAMMA``.
    locked        the names of those features that are read-only (a camera that cannot be set linear).
    gamma_integer ``Gamma`` served as an integer feature of its own register, which bends nothing (a camera whose
                  gamma is not a float: the driver cannot read it as linear or not).
    """

    gamma: float = 1.0
    gamma_enable: bool | None = False
    lut_enable: bool = False
    locked: tuple[str, ...] = ()
    gamma_integer: bool = False


def toned(codes: np.ndarray, full_scale: int, gamma: float) -> np.ndarray:
    """A camera's tone curve on integer codes: round(full_scale (codes / full_scale)^gamma), same dtype; gamma 1
    returns the codes unchanged."""
    if gamma == 1.0:
        return codes
    x = codes.astype(np.float64) / full_scale
    return np.clip(np.rint(full_scale * x ** gamma), 0, full_scale).astype(codes.dtype)


def read_truth(path: str | Path) -> dict[int, ServedFrame]:
    """A ``truth_path`` file -> {device timestamp_ns: ServedFrame}, to score a run on the served camera."""
    out: dict[int, ServedFrame] = {}
    with open(path) as f:
        for line in f:
            if line.strip():
                rec = ServedFrame(**json.loads(line))
                out[rec.timestamp_ns] = rec
    return out


def _tone_xml(tone: ServedTone) -> str:
    """GenICam nodes for ``Gamma`` (a 4-byte float register), ``LUTEnable`` and ``GammaEnable`` (1 on, 0 off; none
    when ``tone.gamma_enable`` is None). A feature named in ``tone.locked`` reads its register through a swiss
    knife, which has no write path: Aravis 0.8 does not enforce a register's AccessMode by default."""

    def feature(kind: str, name: str, reg_kind: str, address: int, body: str) -> str:
        register = (f'<{reg_kind} Name="{name}Register" NameSpace="Custom"><Address>{address:#x}</Address>'
                    "<Length>4</Length><AccessMode>RW</AccessMode><pPort>Device</pPort>"
                    + ("<Sign>Unsigned</Sign>" if reg_kind == "IntReg" else "")
                    + f"<Endianess>BigEndian</Endianess></{reg_kind}>")
        source = f"{name}Register"
        if name in tone.locked:
            knife = "IntSwissKnife" if reg_kind == "IntReg" else "SwissKnife"
            register += (f'\n<{knife} Name="{name}Locked" NameSpace="Custom"><pVariable Name="R">{name}Register'
                         f"</pVariable><Formula>R</Formula></{knife}>")
            source = f"{name}Locked"
        return f'<{kind} Name="{name}" NameSpace="Standard"><pValue>{source}</pValue>{body}</{kind}>\n{register}\n'

    on_off = "<OnValue>1</OnValue><OffValue>0</OffValue>"
    bounds = f"<Min>{GAMMA_RANGE[0]}</Min><Max>{GAMMA_RANGE[1]}</Max>"
    xml = (feature("Integer", "Gamma", "IntReg", _REG_GAMMA_INTEGER, "") if tone.gamma_integer
           else feature("Float", "Gamma", "FloatReg", _REG_GAMMA, bounds))
    xml += feature("Boolean", "LUTEnable", "IntReg", _REG_LUT_ENABLE, on_off)
    if tone.gamma_enable is not None:
        xml += feature("Boolean", "GammaEnable", "IntReg", _REG_GAMMA_ENABLE, on_off)
    return xml


def _genicam_xml(base: str, pixel_format: str, code: int, tone: ServedTone | None = None) -> str:
    """Aravis's fake-camera XML with the PixelFormat enumeration reduced to ``pixel_format``: a client asking for
    another format gets the device's "not offered" answer instead of frames that are not the dataset's; with
    ``tone``, the tone features added (``_tone_xml``)."""
    enum = re.search(r'<Enumeration Name="PixelFormat".*?</Enumeration>', base, re.S)
    if enum is None or "<EnumEntry" not in enum.group(0):
        raise CameraError("GigE Vision server: Aravis's fake camera XML has no PixelFormat enumeration")
    entry = f'<EnumEntry Name="{pixel_format}" NameSpace="Standard"><Value>{code}</Value></EnumEntry>'
    entries = re.sub(r"\s*<EnumEntry.*?</EnumEntry>", "", enum.group(0), flags=re.S)
    reduced = entries.replace("<pValue>", entry + "\n\t\t<pValue>", 1)
    xml = base[:enum.start()] + reduced + base[enum.end():]
    if tone is not None:
        end = xml.rindex("</RegisterDescription>")
        xml = xml[:end] + _tone_xml(tone) + xml[end:]
    return xml


class GvCameraServer:
    """A ``VirtualCamera`` served as a GigE Vision device; see the module docstring.

    dataset, defect_rate, seed, split, cache_mb, empty_rate: as ``VirtualCameraConfig``.
    interface        name ("lo") or IPv4 address to serve on; loopback only unless ``allow_network``.
    serial           device serial number (at most 15 characters).
    truth_path       JSON Lines file that receives one ``ServedFrame`` per frame (appended; line-buffered).
    trigger_poll_hz  how often the device looks for a software trigger (latency <= 1 / trigger_poll_hz).
    keep_recent      how many ``ServedFrame`` records ``recent`` holds.
    tone             the tone features' state at start (``ServedTone``; default linear and writable).
    """

    def __init__(self, dataset: str, *, interface: str = "lo", defect_rate: float = 0.2, seed: int = 0,
                 split: str | None = None, cache_mb: float = 512.0, serial: str = "POLARSIM1",
                 truth_path: str | Path | None = None, allow_network: bool = False,
                 trigger_poll_hz: float = 200.0, keep_recent: int = 100_000, empty_rate: float = 0.0,
                 tone: ServedTone = ServedTone()) -> None:
        if not serial or len(serial) > _SERIAL_MAX or not serial.isascii():
            raise CameraConfigError(f"GigE Vision server: serial {serial!r}: 1-{_SERIAL_MAX} ASCII characters")
        if trigger_poll_hz <= 0:
            raise CameraConfigError(f"GigE Vision server: trigger_poll_hz = {trigger_poll_hz}: must be > 0")
        self.interface = interface
        self.allow_network = allow_network
        self.serial = serial
        self.truth_path = Path(truth_path) if truth_path else None
        self.trigger_poll_hz = trigger_poll_hz
        if not GAMMA_RANGE[0] <= tone.gamma <= GAMMA_RANGE[1]:
            raise CameraConfigError(f"GigE Vision server: tone gamma {tone.gamma}: must be within "
                                    f"[{GAMMA_RANGE[0]:g}, {GAMMA_RANGE[1]:g}]")
        self.tone = tone
        # The virtual camera only draws parts here: the GigE device paces the frames, so no pacing of its own.
        self._camera = VirtualCamera(CameraConfig(trigger="free_run", frame_rate_hz=1e9),
                                     VirtualCameraConfig(dataset, defect_rate, split, seed, cache_mb, empty_rate))
        self.recent: collections.deque[ServedFrame] = collections.deque(maxlen=keep_recent)
        self.n_served = 0
        self.n_defective = 0
        self.address = ""
        self.width = self.height = 0
        self.pixel_format = ""
        self._code = 0
        self._gv: int | None = None  # ArvGvFakeCamera *
        self._fake: int | None = None  # its ArvFakeCamera *, valid while the device lives
        self._callback = _FillPattern(self._fill)  # kept alive as long as the device may call it
        self._truth: IO[str] | None = None
        self._lock = threading.Lock()
        self._warned: set[str] = set()

    # -- life cycle ---------------------------------------------------------------------------------------------
    def start(self) -> GvCameraServer:
        """Load the dataset, then bring the device up on the interface. Raises ``CameraConfigError`` (interface,
        dataset) or ``CameraError`` (the device could not bind its GVCP port)."""
        if self._gv is not None:
            return self
        if not self.allow_network:
            if not is_loopback_interface(self.interface):
                raise CameraConfigError(f"GigE Vision server: interface {self.interface!r} is not a loopback "
                                        "interface; serving a camera on a network needs allow_network "
                                        "(--allow-network)")
            if _discovery_guard() is None and not in_private_netns():
                raise CameraError("GigE Vision server: UDP 255.255.255.255:3956 is held by another process, so "
                                  "the device would answer GigE Vision discovery from the network; stop that "
                                  "process or serve inside a private network namespace (unshare -n)")
        _check_gvcp_port_free(interface_address(self.interface))
        try:
            from model.priors.photometric import frames_per_part
            from sim.dataset import open_dataset

            frames = frames_per_part(open_dataset(self._camera.sim.dataset).dome_segments)
            if frames > 1:  # a part's frames, one per frame sent: each drawn by a trigger of the source
                self._camera.configure(CameraConfig(trigger="software", frame_rate_hz=1e9, frames_per_part=frames))
            self._camera.open()
            self._camera.start()
            self._up()
        except BaseException:
            self.close()
            raise
        _OPEN.add(self)
        log.info("GigE Vision server: %s %dx%d %s at %s (serial %s)", self._camera.sim.dataset, self.width,
                 self.height, self.pixel_format, self.address, self.serial)
        return self

    def _up(self) -> None:
        lib = _lib()
        self.height, self.width = self._camera_frame_shape()
        self.pixel_format = FORMAT_BY_BIT_DEPTH[self._camera.bit_depth]
        self._code = int(pixel_formats.lookup(self.pixel_format).code or 0)
        if self.truth_path is not None:
            self.truth_path.parent.mkdir(parents=True, exist_ok=True)
            self._truth = open(self.truth_path, "a", buffering=1)  # a crash leaves only whole lines
        probe = lib.arv_fake_camera_new(b"probe")
        try:
            base = ctypes.string_at(lib.arv_fake_camera_get_genicam_xml(probe, None)).decode()
        finally:
            lib.g_object_unref(probe)
        xml = _genicam_xml(base, self.pixel_format, self._code, self.tone)
        fd, xml_path = tempfile.mkstemp(prefix="polar-gv-", suffix=".xml")
        try:
            with os.fdopen(fd, "w") as f:
                f.write(xml)
            # the device reads its XML once, here, and starts listening at once
            self._gv = lib.arv_gv_fake_camera_new_full(self.interface.encode(), self.serial.encode(),
                                                       xml_path.encode())
        finally:
            os.unlink(xml_path)
        if not self._gv or not lib.arv_gv_fake_camera_is_running(self._gv):
            raise CameraError(f"GigE Vision server: Aravis cannot serve on interface {self.interface!r}")
        fake = self._fake = lib.arv_gv_fake_camera_get_fake_camera(self._gv)
        for reg, value in ((_REG_SENSOR_WIDTH, self.width), (_REG_SENSOR_HEIGHT, self.height),
                           (_REG_WIDTH, self.width), (_REG_HEIGHT, self.height), (_REG_PIXEL_FORMAT, self._code),
                           (_REG_GAMMA, struct.unpack(">I", struct.pack(">f", self.tone.gamma))[0]),
                           (_REG_GAMMA_ENABLE, int(self.tone.gamma_enable is not False)),
                           (_REG_LUT_ENABLE, int(self.tone.lut_enable))):
            lib.arv_fake_camera_write_register(fake, reg, value)
        for addr, size, text in ((_GVBS_MANUFACTURER, 32, "Polar-Ano"), (_GVBS_MODEL, 32, "VirtualPolarCamera"),
                                 (_GVBS_INFO, 48, Path(self._camera.sim.dataset).name)):
            raw = text.encode()[:size - 1].ljust(size, b"\0")
            lib.arv_fake_camera_write_memory(fake, addr, size, raw)
        lib.arv_fake_camera_set_trigger_frequency(fake, self.trigger_poll_hz)
        lib.arv_fake_camera_set_fill_pattern(fake, self._callback, None)
        ip = ctypes.c_uint32()
        lib.arv_fake_camera_read_register(fake, _GVBS_CURRENT_IP, ctypes.byref(ip))
        self.address = socket.inet_ntoa(struct.pack(">I", ip.value))

    def _camera_frame_shape(self) -> tuple[int, int]:
        from sim.dataset import open_dataset

        m = open_dataset(self._camera.sim.dataset).manifest
        return int(m["height"]), int(m["width"])

    def close(self) -> None:
        """Stop serving (idempotent; never raises). The callback is detached first (a ctypes call: the GIL is
        released while it waits for a frame in progress), then the device's thread is joined."""
        _OPEN.discard(self)
        gv, self._gv = self._gv, None
        if gv:
            lib = _lib()
            lib.arv_fake_camera_set_fill_pattern(lib.arv_gv_fake_camera_get_fake_camera(gv), _FillPattern(), None)
            lib.g_object_unref(gv)  # joins the device thread, closes its sockets
            self._fake = None
        self._camera.close()
        with self._lock:
            if self._truth is not None:
                self._truth.close()
                self._truth = None

    def __enter__(self) -> GvCameraServer:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.close()

    @property
    def running(self) -> bool:
        return self._gv is not None

    # -- frames (in the device's thread) ------------------------------------------------------------------------
    def _fill(self, buffer: int, _data: int, _exposure_us: int, _gain: int, pixel_format: int) -> None:
        """Copy the next part's mosaic (the requested region of it) into the device's frame buffer and record its
        ground truth. Exceptions cannot cross into C: they are logged and the frame goes out as it was."""
        try:
            self._fill_frame(buffer, pixel_format)
        except Exception:
            self._warn_once("fill", "GigE Vision server: cannot fill a frame", exc_info=True)

    def _fill_frame(self, buffer: int, pixel_format: int) -> None:
        lib = _lib()
        if pixel_format != self._code:  # the XML offers one format; a raw register write could still change it
            self._warn_once("format", "GigE Vision server: pixel format 0x%08x requested, serving only %s: frame "
                            "not filled", pixel_format, self.pixel_format)
            return
        w, h = lib.arv_buffer_get_image_width(buffer), lib.arv_buffer_get_image_height(buffer)
        x, y = lib.arv_buffer_get_image_x(buffer), lib.arv_buffer_get_image_y(buffer)
        if self._camera.config.trigger == "software":  # a set's next frame
            self._camera.trigger()
        frame = self._camera.grab(timeout_ms=1000)
        region = frame.raw[y:y + h, x:x + w]
        if region.shape != (h, w):  # a region past the sensor edge: the rest stays black
            padded = np.zeros((h, w), frame.raw.dtype)
            padded[:region.shape[0], :region.shape[1]] = region
            region = padded
        region = self._toned(region)
        region = np.ascontiguousarray(region, dtype=region.dtype.newbyteorder("<"))  # GigE Vision: little-endian
        ctypes.memmove(lib.arv_buffer_get_data(buffer, None), region.ctypes.data, region.nbytes)
        gt = frame.ground_truth
        assert gt is not None and gt.sample_index is not None  # the virtual camera always sets both
        defect = gt.params.get("defect") if gt.params else None
        rec = ServedFrame(int(lib.arv_buffer_get_frame_id(buffer)), int(lib.arv_buffer_get_timestamp(buffer)),
                          gt.sample_index, gt.label, gt.split, defect.get("type") if isinstance(defect, dict) else None,
                          gt.present)
        with self._lock:
            self.recent.append(rec)
            self.n_served += 1
            self.n_defective += rec.label
            if self._truth is not None:
                self._truth.write(json.dumps(asdict(rec)) + "\n")

    def _toned(self, region: np.ndarray) -> np.ndarray:
        """``region``'s codes through the tone features as the client left them (registers read per frame)."""
        lib, fake = _lib(), self._fake

        def register(address: int) -> int:
            value = ctypes.c_uint32()
            lib.arv_fake_camera_read_register(fake, address, ctypes.byref(value))
            return value.value

        full = 2 ** self._camera.bit_depth - 1
        if register(_REG_GAMMA_ENABLE):  # 1 as well when the camera has no GammaEnable
            region = toned(region, full, struct.unpack(">f", struct.pack(">I", register(_REG_GAMMA)))[0])
        if register(_REG_LUT_ENABLE):
            region = toned(region, full, LUT_GAMMA)
        return region

    def _warn_once(self, key: str, msg: str, *args: object, exc_info: bool = False) -> None:
        if key not in self._warned:
            self._warned.add(key)
            log.error(msg, *args, exc_info=exc_info)


@atexit.register
def _close_all() -> None:
    # the device thread must not call into an interpreter that is shutting down
    for server in list(_OPEN):
        server.close()
