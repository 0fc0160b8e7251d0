"""The variation model's shape check: how far the part's bottom edge bends (rule 70,
docs/results/2026-12-05-moulding-kinds.md).

The window statistic judges each place against good parts at that place; a part bowed along its length changes
every place a little and none much, and the registration's affine warp takes up part of what is left. A bow bends
every edge that runs along the part into a parabola, which an affine warp cannot straighten. The check measures it:

1. **Edge** (``find_edge``, at fit time): the bottom edge of the part region, column by column; the longest run of
   columns whose bottom lies within ``EDGE_FIT_PX`` of a robust straight line through them (the body; a plug or a
   rounded end lies off it), trimmed by ``TRIM`` at each end; then in the reference, the row of the strongest vertical
   change within ``EDGE_BAND_PX`` above that line, and a robust straight line through those rows: the edge's line and
   the sign of its change (bright above dark, or dark above bright). No run of ``MIN_RUN`` of the region's columns:
   no edge, and the check is off.
2. **Sag** (``edge_sag``, per part, on its registered intensity): per column of the edge, the row of the strongest
   change of that sign within ``SEARCH_PX`` of the line, to a fraction of a pixel (a parabola through the peak and its
   neighbours); over the columns mapped to [-1, 1] a parabola is fitted, and again without the columns off it by over
   ``ROBUST_K`` robust spreads; the sag is its quadratic coefficient (input px: + when the edge's middle lies higher
   in the frame than its ends, on fewer rows).
3. **Finding** (``ShapeCheck.finding``): the sag as a robust z against the good training parts' (median, 1.4826
   MAD); beyond the largest |z| of the good validation parts (its threshold, ``calibration``), that z over the
   threshold times the window score at the variation model's own 1 % point on those parts, so a part whose sag lies
   beyond every good validation part's scores above that point; within it, 0: the check says nothing, and a part's
   score and rank are the window's (a finding scaled below its threshold too lowered the validation set's image
   AUROC from 0.900 to 0.892 at the same decisions). ``VariationModel.zmaps`` takes the larger of it and the
   window's score, as the residual networks' look does: each finding against its own threshold, one threshold on
   the file.

Buffers (saved with the checkpoint, float64; NaN: not fitted, the check is off and the model scores as before it):
``edge`` (5,) first column, end column (exclusive), the line's row at column 0 and its slope (rows per column), the
sign of the change; ``calibration`` (4,) the good training parts' median sag, its robust spread (input px), the
threshold (robust z) and the window score at the variation model's 1 % point."""

from __future__ import annotations

import math
from collections.abc import Sequence

import cv2
import numpy as np
import torch
from torch import nn

from .errors import ModelError
from .frame_checks import EDGE_BEND_LIMIT

EDGE_FIT_PX = 2.0
"""A column belongs to the straight bottom edge when its region bottom lies within this of the robust line (px)."""
MIN_RUN = 0.4
"""The straight run must span at least this share of the region's columns; fewer: no edge, no check."""
TRIM = 0.1
"""Share of the run left out at each end: a part's corners and chamfers bend the edge there."""
EDGE_BAND_PX = 8
"""In the reference, the edge is sought this far above the region's bottom line (and 2 px below it)."""
SEARCH_PX = 3
"""Per part, the edge is sought this far either side of the reference's edge line (input px)."""
ROBUST_K = 3.0
"""Columns off the first parabola by more than this many robust spreads are left out of the second."""
NO_EDGE = (math.nan,) * 5
NO_CALIBRATION = (math.nan,) * 4


def vertical_change(image: np.ndarray) -> np.ndarray:
    """(H, W) image -> (H - 1, W) float32: row r + 1 minus row r of the image smoothed by a Gaussian of sigma 1 px;
    finite (NaN and Inf read as 0)."""
    f = np.nan_to_num(np.asarray(image, np.float32), nan=0.0, posinf=0.0, neginf=0.0)
    return np.diff(cv2.GaussianBlur(f, (0, 0), 1.0), axis=0)


def robust_line(x: np.ndarray, y: np.ndarray, within: float) -> tuple[np.ndarray, np.ndarray]:
    """A straight line through most of (x, y): the Theil-Sen line (the median of the pairwise slopes, the median
    intercept), fitted again by least squares to the points within ``within`` of it: ((2,) slope and intercept as
    ``np.polyfit``, (N,) bool the points within ``within`` of the result)."""
    i, j = np.triu_indices(len(x), 1)
    dx = x[j] - x[i]
    slope = float(np.median((y[j] - y[i])[dx != 0] / dx[dx != 0]))
    p = np.array([slope, float(np.median(y - slope * x))])
    keep = np.abs(y - np.polyval(p, x)) <= within
    if keep.sum() >= 2:
        p = np.polyfit(x[keep], y[keep], 1)
    return p, np.abs(y - np.polyval(p, x)) <= within


def straight_run(region: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """(H, W) bool part region -> the columns of the longest run whose region bottom lies within ``EDGE_FIT_PX`` of a
    robust straight line through every column's bottom (the body; a plug or a rounded end lies off it), untrimmed,
    and that line ((2,) as ``np.polyfit``); None when the run spans fewer than ``MIN_RUN`` of the region's columns."""
    cols = np.flatnonzero(region.any(0))
    if len(cols) < 10:
        return None
    bottom = np.array([np.flatnonzero(region[:, c]).max() for c in cols], dtype=np.float64)
    p, keep = robust_line(cols.astype(np.float64), bottom, EDGE_FIT_PX)
    runs = np.split(np.arange(len(cols)), np.flatnonzero(np.diff(keep.astype(int)) != 0) + 1)
    run = max((r for r in runs if keep[r[0]]), key=len, default=np.array([], int))
    if len(run) < MIN_RUN * len(cols):
        return None
    return cols[run], p


def strongest_line(change: np.ndarray, cols: np.ndarray, guide: np.ndarray, above: int, below: int
                   ) -> tuple[float, float, float] | None:
    """(H - 1, W) ``vertical_change`` of a reference, columns and (len(cols),) guide rows -> the straight edge through
    each column's strongest change (either sign) from ``above`` rows above the guide to ``below`` rows below it
    (exclusive; negative: above): a robust line through those rows ((row at column 0, slope), points within 1.5 px)
    and the sign of the change along it; None when the change sums to 0 there."""
    rows = []
    for col, line in zip(cols, guide, strict=True):
        lo, hi = max(int(line) - above, 0), min(int(line) + below, change.shape[0])
        rows.append(lo + int(np.argmax(np.abs(change[lo:hi, col]))))
    q, _ = robust_line(cols.astype(np.float64), np.asarray(rows, np.float64), 1.5)
    at = np.clip(np.rint(np.polyval(q, cols)).astype(int), 0, change.shape[0] - 1)
    sign = float(np.sign(np.sum(change[at, cols])))
    return (float(q[1]), float(q[0]), sign) if sign else None


def find_edge(reference: np.ndarray, region: np.ndarray) -> tuple[float, float, float, float, float] | None:
    """(H, W) reference and (H, W) bool part region -> ``edge`` (first column, end column, row at column 0, slope,
    sign) of the part's straight bottom edge (module docstring, step 1), or None when there is none."""
    found = straight_run(region)
    if found is None:
        return None
    run, p = found
    trim = round(TRIM * len(run))
    first, end = int(run[trim]), int(run[-1 - trim]) + 1
    c = np.arange(first, end)
    line = strongest_line(vertical_change(reference), c, np.polyval(p, c), EDGE_BAND_PX, 3)
    return None if line is None else (float(first), float(end), *line)


def edge_rows(intensity: np.ndarray, edge: tuple[float, ...]) -> tuple[np.ndarray, np.ndarray]:
    """(H, W) registered intensity of a part and an ``edge`` (first column, end column, row at column 0, slope, sign)
    -> the columns where it is sought and, per column, the row of the strongest change of its sign within
    ``SEARCH_PX`` of its line, to a fraction of a pixel (a parabola through the peak and its neighbours); input px.
    A column whose searched rows (and the one above and below) hold a NaN is not read: NaN marks pixels the
    registration did not see (``VariationModel.checked_intensity``)."""
    first, end, row0, slope, sign = edge
    change = sign * vertical_change(intensity)
    unseen = ~np.isfinite(intensity)
    rows, used = [], []
    for col in range(int(first), int(end)):
        line = round(row0 + slope * col)
        lo, hi = max(line - SEARCH_PX, 1), min(line + SEARCH_PX + 1, change.shape[0] - 1)
        if hi <= lo or unseen[lo - 1:hi + 2, col].any():
            continue
        r = lo + int(np.argmax(change[lo:hi, col]))
        a, b, d = change[r - 1, col], change[r, col], change[r + 1, col]
        den = a - 2 * b + d
        rows.append(r + (0.5 * (a - d) / den if den < 0 else 0.0))
        used.append(col)
    return np.asarray(used, np.int64), np.asarray(rows, np.float64)


def robust_parabola(u: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """A parabola through (u, rows) ((3,) as ``np.polyfit``), fitted again without the points off the first fit by
    over ``ROBUST_K`` robust spreads (when 10 or more are left)."""
    p = np.polyfit(u, rows, 2)
    off = np.abs(rows - np.polyval(p, u))
    keep = off <= ROBUST_K * max(float(np.median(off)) / 0.6745, 1e-3)
    return np.polyfit(u[keep], rows[keep], 2) if keep.sum() >= 10 else p


def edge_sag(intensity: np.ndarray, edge: tuple[float, ...]) -> float:
    """(H, W) registered intensity of a part and ``edge`` -> the edge's sag in input px (module docstring, step 2);
    NaN when too few columns show it."""
    used, rows = edge_rows(intensity, edge)
    if len(rows) < 10:
        return math.nan
    return float(robust_parabola(np.interp(used, (edge[0], edge[1] - 1), (-1.0, 1.0)), rows)[0])


def finite_sags(sags: np.ndarray, which: str) -> np.ndarray:
    """The finite ones of ``sags`` (a part whose edge was not seen has NaN); ModelError with fewer than 10, naming
    ``which`` parts."""
    s = np.asarray(sags, np.float64)
    s = s[np.isfinite(s)]
    if len(s) < 10:
        raise ModelError(f"shape check: the edge is seen on {len(s)} {which} parts; it needs 10")
    return s


def centre_spread(sags: np.ndarray, which: str) -> tuple[float, float]:
    """Median and robust spread (1.4826 MAD) of the finite ``sags`` (input px); ModelError with fewer than 10 or a
    spread of 0 (``finite_sags``)."""
    s = finite_sags(sags, which)
    centre = float(np.median(s))
    spread = float(np.median(np.abs(s - centre))) * 1.4826
    if not spread > 0:
        raise ModelError(f"shape check: the {which} parts' sags do not spread")
    return centre, spread


def held_z(sags: np.ndarray, centre: float, spread: float) -> float:
    """The largest robust z of the finite ``sags`` of held (validation) parts against ``centre`` and ``spread``;
    ModelError with fewer than 10 (``finite_sags``)."""
    return float(np.abs(finite_sags(sags, "good validation") - centre).max()) / spread


class ShapeCheck(nn.Module):
    """The shape check's edge and calibration (module docstring); off until ``fit``."""

    def __init__(self) -> None:
        super().__init__()
        self.register_buffer("edge", torch.tensor(NO_EDGE, dtype=torch.float64))
        self.register_buffer("calibration", torch.tensor(NO_CALIBRATION, dtype=torch.float64))

    @property
    def fitted(self) -> bool:
        """Whether the check is on: an edge and a calibration."""
        return bool(torch.isfinite(self.edge).all() and torch.isfinite(self.calibration).all())

    def find(self, reference: np.ndarray, region: np.ndarray) -> bool:
        """Set ``edge`` from the variation model's reference and region (``find_edge``); clears the calibration.
        Whether an edge was found."""
        edge = find_edge(reference, region)
        self.edge.copy_(torch.tensor(NO_EDGE if edge is None else edge, dtype=torch.float64))
        self.calibration.copy_(torch.tensor(NO_CALIBRATION, dtype=torch.float64))
        return edge is not None

    def sag(self, intensity: np.ndarray) -> float:
        """A part's registered intensity -> its edge's sag (input px; NaN without an edge or where none is seen)."""
        edge = tuple(float(v) for v in self.edge)
        return edge_sag(intensity, edge) if all(math.isfinite(v) for v in edge) else math.nan

    def calibrate(self, train_sags: np.ndarray, val_sags: np.ndarray, window_at_threshold: float) -> None:
        """Set ``calibration`` from the good training parts' and the good validation parts' sags (NaN ones left out)
        and the window score at the variation model's 1 % point on those validation parts. ModelError with fewer
        than 10 sags of either, or a spread of 0."""
        centre, spread = centre_spread(train_sags, "good training")
        self._set(centre, spread, held_z(val_sags, centre, spread), window_at_threshold)

    def calibrate_crossed(self, sags: np.ndarray, splits: Sequence[tuple[np.ndarray, np.ndarray]],
                          window_at_threshold: float) -> None:
        """Set ``calibration`` from one set of good parts' ``sags`` (N,) by cross-fitting (``station adapt``): each
        split's held parts' z against the median and spread of its fitted parts' (``splits``: (fit, held) index
        arrays), the threshold the largest held z; the median and spread of all of them; ``window_at_threshold``
        the window's 1 % point on the held parts. ModelError as ``calibrate``, for each split."""
        s = np.asarray(sags, np.float64)
        z = [held_z(s[held], *centre_spread(s[fit], "fitted good")) for fit, held in splits]
        self._set(*centre_spread(s, "good"), max(z), window_at_threshold)

    def _set(self, centre: float, spread: float, threshold: float, window_at_threshold: float) -> None:
        if not window_at_threshold > 0:
            raise ModelError("shape check: the window's threshold is not > 0")
        self.calibration.copy_(torch.tensor([centre, spread, max(threshold, 1.0), window_at_threshold],
                                            dtype=torch.float64))

    def bend(self, sag: float) -> float:
        """A part's sag -> how far its edge bends, as its robust z over the check's threshold (signed as the sag: + the
        edge's middle higher in the frame than its ends); beyond +-1 (``model.draem.frame_checks.EDGE_BEND_LIMIT``)
        it bends further than any good validation part's. NaN when the check is off or the sag is NaN."""
        if not self.fitted or not math.isfinite(sag):
            return math.nan
        centre, spread, threshold, _ = (float(v) for v in self.calibration)
        return (sag - centre) / spread / threshold

    def finding(self, sag: float) -> float:
        """A part's sag -> its finding in the window's score units (module docstring, step 3); 0.0 within the
        threshold, when the check is off or the sag is NaN (the part is still judged by the window)."""
        bend = abs(self.bend(sag))
        return bend * float(self.calibration[3]) if bend > EDGE_BEND_LIMIT else 0.0

    def check(self) -> None:
        """ModelError unless both buffers are all NaN (off) or all finite with the spread, threshold and window > 0:
        a file whose check was half switched off is refused, not judged without it."""
        for name, t in (("edge", self.edge), ("calibration", self.calibration)):
            if not (bool(torch.isnan(t).all()) or bool(torch.isfinite(t).all())):
                raise ModelError(f"shape check: {name} is partly NaN or Inf")
        if bool(torch.isnan(self.edge).all()) != bool(torch.isnan(self.calibration).all()):
            raise ModelError("shape check: edge and calibration are not both set or both NaN")
        if torch.isfinite(self.calibration).all() and not bool((self.calibration[1:] > 0).all()):
            raise ModelError("shape check: its spread, threshold and window score must be > 0")
