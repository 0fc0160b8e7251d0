"""Polar-Ano Station: the inspection application (CLI, config, loop, log, viewer)."""

__version__ = "0.1.0"
