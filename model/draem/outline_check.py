"""The variation model's outline check: a short step along the part's long edges (flash, a chipped or short edge;
docs/results/2026-12-05-outline.md).

A fin of flash at the parting line moves the part's outline by a step: at the front face's top edge it continues the
top face below the face's edge by 0.5-2 input rows over 2-10 mm (8-40 input columns). The window judges each place
against good parts at that place, and the part's edges are where good parts vary most after registration, so it
misses most of them; the shape check reads a whole edge as a parabola, which a short step does not move. This check
reads the edges column by column against the good parts' at the same column:

1. **Edges** (``find_edges``, at fit time, from the variation model's reference and region): the columns of the
   part's straight bottom run (``shape_check.straight_run``, untrimmed) less ``MARGIN_PX`` at each end; the bottom
   edge, the reference's strongest vertical change within ``shape_check.EDGE_BAND_PX`` above the region's bottom
   line (as the shape check's), and the top edge, its strongest change ``TOP_BAND_PX`` above that edge (on the
   shipped part the front face's top edge), each a robust straight line and the sign of its change.
2. **Deviation** (per part, on its registered intensity, NaN where the registration did not see the frame:
   ``VariationModel.checked_intensity``; a column whose searched rows hold one is not read): per column the edge's
   row to a fraction of a pixel (``shape_check.edge_rows``), less the part's own robust parabola through them (so a
   bend stays the shape check's), less the good training parts' median at that column; then its mean over each run
   of ``RUN_PX`` columns (about 4 mm on the shipped part).
3. **Step** (``OutlineCheck.step``): each run's mean against the good training parts' at that run (median, 1.4826
   MAD, floored at ``SPREAD_FLOOR_PX``) as a robust z; per edge, its largest |z| over the edge's threshold (the
   largest of the good calibration parts'); the part's step the larger of the two edges'. Beyond 1
   (``frame_checks.EDGE_STEP_LIMIT``) the part's outline steps further than any good calibration part's, and its
   finding is the step times the window score at the variation model's own 1 % point, as the shape check's (within
   it 0: the check says nothing).

Buffers (saved with the checkpoint, float64; NaN: not fitted, the check is off and the model scores as before it):
``edges`` (2, 5) per edge (bottom, top) the first column, end column (exclusive), the line's row at column 0, its
slope and the sign of the change; ``median`` (2, W) per column, the good training parts' median deviation; ``centre``
and ``spread`` (2, W) per run's first column, the runs' median and robust spread; ``calibration`` (3,) the bottom
and the top edge's threshold (robust z) and the window score at the variation model's 1 % point. W: the input width.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence

import numpy as np
import torch
from torch import nn

from .errors import ModelError
from .frame_checks import EDGE_STEP_LIMIT
from .shape_check import (
    EDGE_BAND_PX,
    SEARCH_PX,
    edge_rows,
    robust_parabola,
    straight_run,
    strongest_line,
    vertical_change,
)

MARGIN_PX = 6
"""Columns left out at each end of the straight run: a part's corners bend its edges there, and good parts' edges
wander most (on the shipped part the good calibration parts' largest runs lay within 4 columns of the ends)."""
TOP_BAND_PX = (40, -12)
"""The top edge is sought from 40 rows above the bottom edge to 12 rows above it (``strongest_line``'s above and
below, input px)."""
RUN_PX = 16
"""Columns a run's mean is taken over (input px; about 4 mm on the shipped part; fins are 2-10 mm long)."""
SPREAD_FLOOR_PX = 0.02
"""A run's robust spread is floored at this (input px)."""
MIN_PARTS = 10
"""Fewest parts whose edges are seen that set the medians, spreads or thresholds."""


def find_edges(reference: np.ndarray, region: np.ndarray) -> np.ndarray | None:
    """(H, W) reference and (H, W) bool part region -> ``edges`` (2, 5) (module docstring, step 1), or None when the
    region has no straight run or an edge shows no change."""
    found = straight_run(region)
    if found is None:
        return None
    run, p = found
    first, end = int(run[0]) + MARGIN_PX, int(run[-1]) + 1 - MARGIN_PX
    if end - first < 2 * RUN_PX:
        return None
    c = np.arange(first, end)
    change = vertical_change(reference)
    bottom = strongest_line(change, c, np.polyval(p, c), EDGE_BAND_PX, 3)
    if bottom is None:
        return None
    top = strongest_line(change, c, bottom[0] + bottom[1] * c, *TOP_BAND_PX)
    if top is None:
        return None
    return np.array([(first, end, *bottom), (first, end, *top)], np.float64)


def deviations(intensity: np.ndarray, edges: np.ndarray, width: int) -> np.ndarray:
    """(H, W) registered intensity of a part and ``edges`` -> (2, width) each edge's row per column less the part's
    robust parabola through them (module docstring, step 2, before the median), NaN outside the edge's columns, at a
    column whose row lies over ``SEARCH_PX`` + 1 from the edge's line, and where fewer than 10 columns show it."""
    out = np.full((2, width), np.nan)
    for e, edge in enumerate(edges):
        used, rows = edge_rows(intensity, tuple(float(v) for v in edge))
        if len(rows) < 10:
            continue
        # a row beyond the searched ones is no reading (its sub-pixel vertex ran off a peak at the search's end)
        ok = np.abs(rows - (edge[2] + edge[3] * used)) <= SEARCH_PX + 1.0
        used, rows = used[ok], rows[ok]
        if len(rows) < 10:
            continue
        u = np.interp(used, (edge[0], edge[1] - 1), (-1.0, 1.0))
        out[e, used] = rows - np.polyval(robust_parabola(u, rows), u)
    return out


def run_means(d: np.ndarray) -> np.ndarray:
    """(..., W) deviations -> (..., W) their mean over the ``RUN_PX`` columns from each column on (NaN where a run
    leaves the edge or holds a NaN column)."""
    def window_sum(a: np.ndarray) -> np.ndarray:
        c = np.cumsum(np.concatenate([np.zeros((*a.shape[:-1], 1)), a], -1), -1)
        return c[..., RUN_PX:] - c[..., :-RUN_PX]

    seen = np.isfinite(d)
    out = np.full(d.shape, np.nan)
    n = window_sum(seen.astype(np.float64))
    out[..., : d.shape[-1] - RUN_PX + 1] = np.where(n == RUN_PX, window_sum(np.where(seen, d, 0.0)) / RUN_PX, np.nan)
    return out


def run_statistics(d: np.ndarray, which: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(N, 2, W) good parts' deviations -> (2, W) per-column median, (2, W) per run its median and robust spread
    (module docstring, steps 2-3). ModelError with fewer than ``MIN_PARTS`` parts whose edges are seen, naming
    ``which`` parts."""
    seen = np.isfinite(d).any(2).all(1)
    if seen.sum() < MIN_PARTS:
        raise ModelError(f"outline check: the edges are seen on {int(seen.sum())} {which} parts; it needs {MIN_PARTS}")
    d = d[seen]
    with warnings.catch_warnings():  # columns off the edges: all NaN, and NaN they stay
        warnings.simplefilter("ignore", RuntimeWarning)
        median = np.nanmedian(d, 0)
        r = run_means(d - median)
        centre = np.nanmedian(r, 0)
        spread = np.maximum(1.4826 * np.nanmedian(np.abs(r - centre), 0), SPREAD_FLOOR_PX)
    return median, centre, np.where(np.isfinite(centre), spread, np.nan)


def edge_z(d: np.ndarray, median: np.ndarray, centre: np.ndarray, spread: np.ndarray) -> np.ndarray:
    """(N, 2, W) parts' deviations -> (N, 2) each edge's largest |robust z| over its runs (NaN where none is seen)."""
    z = np.abs((run_means(d - median) - centre) / spread)
    with np.errstate(all="ignore"):
        return np.where(np.isfinite(z).any(2), np.nanmax(np.where(np.isfinite(z), z, -np.inf), 2), np.nan)


def held_thresholds(z: np.ndarray) -> np.ndarray:
    """(N, 2) held parts' edge z -> (2,) each edge's threshold, the largest of them (at least 1). ModelError with
    fewer than ``MIN_PARTS`` parts whose edges are seen."""
    seen = np.isfinite(z).all(1)
    if seen.sum() < MIN_PARTS:
        raise ModelError(f"outline check: the edges are seen on {int(seen.sum())} good validation parts; it needs "
                         f"{MIN_PARTS}")
    return np.maximum(z[seen].max(0), 1.0)


class OutlineCheck(nn.Module):
    """The outline check's edges, statistics and calibration (module docstring); off until fitted."""

    def __init__(self, width: int) -> None:
        super().__init__()
        self.register_buffer("edges", torch.full((2, 5), math.nan, dtype=torch.float64))
        for name in ("median", "centre", "spread"):
            self.register_buffer(name, torch.full((2, width), math.nan, dtype=torch.float64))
        self.register_buffer("calibration", torch.full((3,), math.nan, dtype=torch.float64))

    @property
    def fitted(self) -> bool:
        """Whether the check is on: edges and a calibration."""
        return bool(torch.isfinite(self.edges).all() and torch.isfinite(self.calibration).all())

    def find(self, reference: np.ndarray, region: np.ndarray) -> bool:
        """Set ``edges`` from the variation model's reference and region (``find_edges``); clears the rest. Whether
        both edges were found."""
        edges = find_edges(reference, region)
        self.clear()
        if edges is not None:
            self.edges.copy_(torch.from_numpy(edges))
        return edges is not None

    def clear(self) -> None:
        """Switch the check off: every buffer NaN."""
        for name in ("edges", "median", "centre", "spread", "calibration"):
            getattr(self, name).fill_(math.nan)

    def deviations(self, intensity: np.ndarray) -> np.ndarray:
        """A part's registered intensity -> its (2, W) deviations (``deviations``; all NaN without edges)."""
        if not torch.isfinite(self.edges).all():
            return np.full(tuple(self.median.shape), np.nan)
        return deviations(intensity, self.edges.numpy(), self.median.shape[1])

    def calibrate(self, train: np.ndarray, val: np.ndarray, window_at_threshold: float) -> None:
        """Set the statistics from the good training parts' (N, 2, W) deviations and the thresholds from the good
        validation parts', with the window score at the variation model's 1 % point on those. ModelError with too
        few parts (``MIN_PARTS``) or a window score not > 0."""
        stats = run_statistics(train, "good training")
        self._set(stats, held_thresholds(edge_z(val, *stats)), window_at_threshold)

    def calibrate_crossed(self, d: np.ndarray, splits: Sequence[tuple[np.ndarray, np.ndarray]],
                          window_at_threshold: float) -> None:
        """Set the statistics and thresholds from one set of good parts' (N, 2, W) deviations by cross-fitting
        (``station adapt``): each split's held parts' z against its fitted parts' statistics (``splits``: (fit, held)
        index arrays), each edge's threshold the largest held z; the statistics from all of them. ModelError as
        ``calibrate``, for each split."""
        z = np.concatenate([edge_z(d[held], *run_statistics(d[fit], "fitted good")) for fit, held in splits])
        self._set(run_statistics(d, "good"), held_thresholds(z), window_at_threshold)

    def _set(self, stats: tuple[np.ndarray, np.ndarray, np.ndarray], thresholds: np.ndarray,
             window_at_threshold: float) -> None:
        if not window_at_threshold > 0:
            raise ModelError("outline check: the window's threshold is not > 0")
        for name, value in zip(("median", "centre", "spread"), stats, strict=True):
            getattr(self, name).copy_(torch.from_numpy(np.asarray(value, np.float64)))
        self.calibration.copy_(torch.tensor([*thresholds, window_at_threshold], dtype=torch.float64))

    def step(self, intensity: np.ndarray) -> float:
        """A part's registered intensity -> how far its outline steps: the larger of its edges' largest run z over
        that edge's threshold (module docstring, step 3); beyond ``EDGE_STEP_LIMIT`` further than any good
        calibration part's. NaN when the check is off or neither edge is seen."""
        if not self.fitted:
            return math.nan
        z = edge_z(self.deviations(intensity)[None], self.median.numpy(), self.centre.numpy(),
                   self.spread.numpy())[0]
        over = z / self.calibration.numpy()[:2]
        return float(np.nanmax(over)) if np.isfinite(over).any() else math.nan

    def finding(self, step: float) -> float:
        """A part's step -> its finding in the window's score units; 0.0 within the limit, when the check is off or
        the step is NaN (the part is still judged by the window)."""
        return step * float(self.calibration[2]) if self.fitted and step > EDGE_STEP_LIMIT else 0.0

    def check(self) -> None:
        """ModelError unless the check is off (edges or calibration all NaN) or fitted with thresholds and window > 0:
        a file whose check was half switched off is refused, not judged without it."""
        for name in ("edges", "calibration"):
            t = getattr(self, name)
            if not (bool(torch.isnan(t).all()) or bool(torch.isfinite(t).all())):
                raise ModelError(f"outline check: {name} is partly NaN or Inf")
        if bool(torch.isnan(self.edges).all()) != bool(torch.isnan(self.calibration).all()):
            raise ModelError("outline check: edges and calibration are not both set or both NaN")
        if self.fitted and not bool((self.calibration > 0).all()):
            raise ModelError("outline check: its thresholds and window score must be > 0")
        if bool(torch.isinf(torch.stack([self.median, self.centre, self.spread])).any()):
            raise ModelError("outline check: its statistics hold Inf")
