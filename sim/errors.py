"""Errors of the sim package: bad scene/dataset input, raised before any rendering starts."""

from __future__ import annotations


class SimError(Exception):
    """Bad input to the renderer or dataset (config value, mesh file, material name, dataset folder).

    The message names the file, key or sample; ``station`` prints it as one line.
    """
