"""``compute_priors``: raw mosaic -> the polarimetric priors a consumer asks for, and nothing more."""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from .conventions import MosaicLayout
from .demosaic import Stokes, mosaic_to_stokes
from .mosaic import NormalizedMosaic, normalize_mosaic
from .photometric import DOME_PAIRS, check_tilts, frames_per_part, mean_stokes, tilt_maps
from .stokes import aolp, aolp_vector, dolp, unpolarized_intensity

PRIOR_KEYS = ("intensity", "dolp", "aolp", "aolp_cos", "aolp_sin", "s0", "s1", "s2", "tilt_x", "tilt_y")
"""Everything ``compute_priors`` can return; meanings and units in ``conventions.py``; the tilts
(``photometric.DOME_PAIRS``) only from a frame per dome segment (``compute_set_priors``)."""


@dataclass(frozen=True)
class Priors(Mapping[str, np.ndarray]):
    """Float32 (H', W') arrays keyed by prior name, plus a report of what was wrong with the input.

    ``invalid`` (mosaic resolution, bool) marks NaN/Inf or out-of-range input pixels that were replaced;
    None when the input was clean. ``n_saturated`` counts pixels at full scale (their Stokes are biased).
    """

    arrays: dict[str, np.ndarray]
    n_nonfinite: int = 0
    n_out_of_range: int = 0
    n_saturated: int = 0
    invalid: np.ndarray | None = field(default=None, repr=False)

    def __getitem__(self, key: str) -> np.ndarray:
        return self.arrays[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self.arrays)

    def __len__(self) -> int:
        return len(self.arrays)


def check_prior_names(priors: Iterable[str]) -> tuple[str, ...]:
    names = tuple(priors)
    unknown = [p for p in names if p not in PRIOR_KEYS]
    if unknown or not names:
        raise ValueError(f"unknown or no priors {unknown or names}; choose from {', '.join(PRIOR_KEYS)}")
    return names


def compute_priors(raw: np.ndarray, layout: str | MosaicLayout = "imx250mzr", method: str = "bilinear",
                   priors: Iterable[str] = ("intensity", "dolp", "aolp"), bit_depth: int | None = None
                   ) -> Priors:
    """Demosaic a raw polarizer mosaic and compute the requested priors.

    Parameters
    ----------
    raw : (H, W) uint8, uint16 or float array, H and W even. Integers are codes of ``bit_depth`` significant
        bits (default: the dtype's width; e.g. 12 for a Mono12 camera in uint16); floats are full-scale units.
    layout : mosaic layout name or ``MosaicLayout`` (default: Sony IMX250MZR).
    method : demosaicking method name (see ``model.priors.demosaic.METHODS``).
    priors : names from ``PRIOR_KEYS``; only these and what they need (S0 for intensity; S0, S1, S2 for
        polarization) are computed and returned.

    Returns
    -------
    Priors : mapping of float32 (H', W') arrays (H' = H, or H/2 for half-resolution methods); never NaN or
        Inf; dolp in [0, 1], aolp in [0, pi). Conventions: ``model.priors.conventions``.
    """
    return compute_set_priors((raw,), (), layout, method, priors, bit_depth)


def compute_set_priors(raws: Sequence[np.ndarray], segments: Sequence[float] | None,
                       layout: str | MosaicLayout = "imx250mzr",
                       method: str = "bilinear", priors: Iterable[str] = ("intensity", "dolp", "aolp"),
                       bit_depth: int | None = None) -> Priors:
    """``compute_priors`` for one part imaged once per dome segment (``model.priors.photometric``): ``raws`` in the
    order of ``segments`` (azimuths, degrees). Intensity and polarization come from the frames' mean Stokes (the
    uniform dome's frame), the tilts from the pairs' S0. One frame with no segments is ``compute_priors`` (which
    calls this). ``segments`` None: the frames' azimuths are not known (a saved reject's frames), so any number of
    frames gives the mean's priors, and no tilt.
    The report is the worst frame's: the largest counts of invalid and saturated pixels (so a fraction of one
    frame's pixels), and every frame's invalid pixels."""
    names = check_prior_names(priors)
    if segments is None:
        segments = ()
    elif len(raws) != frames_per_part(segments):
        raise ValueError(f"{len(raws)} frames for {len(segments)} dome segments")
    check_tilts(names, segments)
    norms, stokes = set_stokes(raws, layout, method, needs_polarization(names), bit_depth)
    invalid = [n.invalid for n in norms if n.invalid is not None]
    return Priors(set_priors_from_stokes(names, segments, stokes), max(n.n_nonfinite for n in norms),
                  max(n.n_out_of_range for n in norms), max(n.n_saturated for n in norms),
                  invalid[0] if len(invalid) == 1 else np.logical_or.reduce(invalid) if invalid else None)


def set_stokes(raws: Sequence[np.ndarray], layout: str | MosaicLayout, method: str, polarization: bool,
               bit_depth: int | None) -> tuple[list[NormalizedMosaic], list[Stokes]]:
    """Each frame of a part normalised (``normalize_mosaic``: full-scale units and what was wrong with it) and
    demosaiced to (S0, S1, S2) (S1, S2 None unless ``polarization``); ValueError when the frames differ in shape."""
    norms = [normalize_mosaic(raw, bit_depth) for raw in raws]
    if len({n.data.shape for n in norms}) != 1:
        raise ValueError(f"the frames differ in shape: {sorted({n.data.shape for n in norms})}")
    return norms, [mosaic_to_stokes(n.data, layout, method, polarization) for n in norms]


def set_priors_from_stokes(names: Sequence[str], segments: Sequence[float], stokes: Sequence[Stokes]
                           ) -> dict[str, np.ndarray]:
    """The priors ``names`` of one part from its frames' Stokes (``segments`` order): intensity and polarization
    from the frames' mean Stokes, the tilts from opposite segments' S0."""
    arrays = priors_from_stokes(names, *mean_stokes(stokes))
    arrays.update(tilt_maps(names, segments, [s[0] for s in stokes]))
    return arrays


def needs_polarization(names: Iterable[str]) -> bool:
    """Whether any of the prior ``names`` needs S1, S2 (everything but intensity, S0 and the tilts does)."""
    return any(n not in ("intensity", "s0", *DOME_PAIRS) for n in names)


def priors_from_stokes(names: Iterable[str], s0: np.ndarray, s1: np.ndarray | None, s2: np.ndarray | None
                       ) -> dict[str, np.ndarray]:
    """The requested priors from (S0, S1, S2), plus the Stokes images themselves (S1, S2 when given)."""
    names = set(names)
    out: dict[str, np.ndarray] = {"s0": s0}
    if s1 is not None and s2 is not None:
        out["s1"], out["s2"] = s1, s2
    if "intensity" in names:
        out["intensity"] = unpolarized_intensity(s0)
    if "dolp" in names:
        out["dolp"] = dolp(s0, s1, s2)
    if "aolp" in names:
        out["aolp"] = aolp(s1, s2)
    if "aolp_cos" in names or "aolp_sin" in names:
        out["aolp_cos"], out["aolp_sin"] = aolp_vector(s1, s2)
    return out
