"""User-facing errors: the CLI prints these as one line (exit 2) instead of a traceback."""

from __future__ import annotations

from drivers.errors import DriverError
from model.draem.errors import ModelError
from sim.errors import SimError


class UserError(Exception):
    """Bad input from the user or the world (config, file, device): message names the file, key or frame."""


USER_ERRORS: tuple[type[BaseException], ...] = (UserError, FileNotFoundError, PermissionError, SimError, DriverError,
                                                ModelError)
"""Caught by ``station.cli.main``. Packages below ``station`` (model, sim, drivers) cannot import this module:
their own error base classes are added here as they are written."""
