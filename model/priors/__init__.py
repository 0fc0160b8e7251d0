"""Polarization priors core: mosaic layouts, demosaicking, Stokes, DoLP, AoLP (numpy; no torch import).

Conventions live in ``model.priors.conventions``; the torch path is ``model.priors.torch_ops``.
"""

from .api import PRIOR_KEYS, Priors, compute_priors
from .conventions import CONVENTION_VERSION, IMX250MZR, LAYOUTS, MosaicLayout, get_layout
from .demosaic import METHODS, demosaic, mosaic_to_stokes
from .mosaic import normalize_mosaic, stokes_to_mosaic

__all__ = [
    "CONVENTION_VERSION", "IMX250MZR", "LAYOUTS", "METHODS", "PRIOR_KEYS", "MosaicLayout", "Priors",
    "compute_priors", "demosaic", "get_layout", "mosaic_to_stokes", "normalize_mosaic", "stokes_to_mosaic",
]
