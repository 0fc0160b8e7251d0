"""Errors of the drivers package. ``station.errors.USER_ERRORS`` includes ``DriverError`` so the CLI prints
one line; every message names the device, port, pixel format code or frame it is about."""

from __future__ import annotations


class DriverError(Exception):
    """Base of every error raised on purpose by ``drivers``."""


class CameraError(DriverError):
    """A camera refused an operation (open, configure, start) or was used out of order."""


class CameraNotFound(CameraError):
    """No camera answers to the requested device id, serial number or address."""


class CameraConfigError(CameraError):
    """A configuration value the camera (or the driver) cannot take; names the feature and the value."""


class CameraTimeout(CameraError):
    """No complete frame arrived within the grab timeout. The camera is still usable: grab again."""


class CameraLost(CameraError):
    """The camera stopped answering (unplugged, powered off, network gone) and could not be reconnected.

    Statistics stay readable; ``close()`` is still safe to call."""


class TriggerFailed(DriverError):
    """The software trigger command failed again after the camera answered a reconnect: this part has no frame. Not
    a ``CameraError``: the station rejects the part and goes on (``station.loop.MAX_UNUSABLE_FRAMES``)."""


class PixelFormatError(DriverError):
    """A pixel format code or name the decoder does not know, or a buffer whose size does not fit it."""


class LineIOError(DriverError):
    """The serial line to the PLC cannot be opened or used (bad port, peer gone and reconnects exhausted)."""
