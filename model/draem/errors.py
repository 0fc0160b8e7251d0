"""Errors of the detector package; the station adds ``ModelError`` to its one-line user errors."""

from __future__ import annotations


class ModelError(Exception):
    """Bad model input, configuration or artefact; the message names the file, key or tensor and what is wrong."""


class CheckpointError(ModelError):
    """A checkpoint or its JSON sidecar is missing, unreadable or does not match what the caller expects."""


class ConfigError(ModelError):
    """A configuration value is out of its range; ``key`` names the field (a command maps it to its flag)."""

    def __init__(self, key: str, message: str) -> None:
        super().__init__(message)
        self.key = key
