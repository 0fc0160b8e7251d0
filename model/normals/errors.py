"""Errors of the normal-estimation package (a ``ModelError``, so the station prints them as one line)."""

from __future__ import annotations

from model.draem.errors import CheckpointError, ModelError


class NormalsError(ModelError):
    """Bad input to a normal estimator: the message names the array or file and what is wrong."""


class NormalsCheckpointError(NormalsError, CheckpointError):
    """A normal-estimator checkpoint or its sidecar is missing, unreadable or does not match."""
