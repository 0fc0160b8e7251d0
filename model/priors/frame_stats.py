"""Brightness and polarization statistics of one frame, and the range a model was trained on (numpy only).

A detector is trained on frames of one brightness: a camera whose exposure, gain or light differs gives inputs the
model never saw, and its scores (and false rejects) move although no part changed. These statistics make that
visible: the model records the range of its training (or adaptation) frames, ``station capture`` prints them per
frame, and ``station.drift.DriftMonitor`` compares a rolling window of live frames with the recorded range.

Statistics over the station's region of interest (the centre square of the frame, ``centre_square``;
no object mask is needed, so a station can compute them on every frame):

    median_level      median unpolarized intensity (S0/2, full-scale units 0..1): the exposure knob
    high_level        95th percentile of the intensity: where highlights sit, how close to clipping
    clipped_fraction  share of mosaic pixels at full scale (``Priors.n_saturated``; whole frame when only the
                      count is known), else of intensity pixels >= ``CLIP_LEVEL``
    dolp_level        median degree of linear polarization: changes with light, belt and lens, not with exposure
    dark_level        0.5th percentile of the intensity: the frame's darkest pixels (shadows, a dark belt). A camera's
                      black level the station is not told adds to every code, so it lifts this floor by the
                      pedestal's share of full scale, where an exposure change only scales it (a 256-code pedestal
                      in 12 bits: 0.03 -> 0.09; docs/results/2026-12-04-ship-otherwise.md)
    edge_level        how sharp the frame is: the 99th percentile of the intensity's steps between neighbours (1 px
                      apart on the 640 x 480 renders, side / 480 px on a larger frame) over the highlight level. A
                      lens out of focus or a moving part lowers it; an exposure change does not move it
                      (``edge_level``; docs/results/2026-12-04-focus.md)
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import asdict, dataclass

import numpy as np

CLIP_LEVEL = 0.99
"""Intensity at or above which a pixel counts as clipped when the mosaic's saturation count is not known."""

STAT_NAMES = ("median_level", "high_level", "clipped_fraction", "dolp_level", "dark_level", "edge_level")
DARK_PERCENTILE = 0.5
"""Percentile of the intensity ``dark_level`` reads: low enough for the shadows, high enough not to be one pixel."""
EDGE_PERCENTILE = 99.0
"""Percentile of the 1-pixel steps ``edge_level`` reads: the part's edges and the panel's stripes, not the noise."""
EDGE_STRIDE = 3
"""Anchor spacing of ``edge_level``'s steps, in steps: a ninth of the pixels, the same wherever it is computed."""
EDGE_SCALE = 480
"""Side (px) of the centre square at which ``edge_level``'s step is 1 px: the 640 x 480 renders'. On a larger frame
of the same scene the step spans side / 480 px (4 px on the IMX250MZR's 2048 rows), so a frame's sharpness is read at
the scene scale the model was trained at, not at the sensor's pixel pitch."""


@dataclass(frozen=True)
class FrameStatistics:
    """See the module docstring; all values are fractions of full scale or shares in [0, 1]."""

    median_level: float
    high_level: float
    clipped_fraction: float
    dolp_level: float
    dark_level: float | None = None
    """None where not measured; a range over such frames leaves it out (``StatisticsRange.from_frames``)."""
    edge_level: float | None = None
    """As ``dark_level``: None where not measured."""

    def as_dict(self) -> dict[str, float | None]:
        return asdict(self)

    def describe(self) -> str:
        dark = f" p0.5 {self.dark_level:.3f}" if self.dark_level is not None else ""
        edge = f", edges {self.edge_level:.3f}" if self.edge_level is not None else ""
        return (f"level median {self.median_level:.3f} p95 {self.high_level:.3f}{dark}, clipped "
                f"{100 * self.clipped_fraction:.2f} %, DoLP median {self.dolp_level:.3f}{edge}")


def centre_square(height: int, width: int, frame_aspect: float = 0.0) -> tuple[int, int, int, int]:
    """(top, left, side, side) of the centre square: the station's region, the model's (``model.draem.roi``) and
    these statistics'; top, left and side even, so a crop of the raw mosaic keeps its 2x2 polarizer layout.

    ``frame_aspect``: width / height of the frames a model was trained on (0: not known). The lens's field of view
    runs along the width (the renders' ``fov_axis`` x, ``sim.scene``), so a frame of the same width and another
    height shows the same scene at the same scale, with more above and below. On a frame taller than the training
    frames (the whole IMX250MZR sensor, 2448 x 2048, against 640 x 480 renders: 4:3 crops of its width) the square
    is that of the training shape's frame of the same width (a 1836 px square instead of 2048), so the part keeps
    the size the model was trained at (docs/results/2026-11-26-frame-shape.md). Otherwise the side is
    min(height, width)."""
    side = min(height, width)
    if frame_aspect > 0 and width < frame_aspect * height:
        side = min(side, int(width / frame_aspect))
    side &= ~1
    return ((height - side) // 2) & ~1, ((width - side) // 2) & ~1, side, side


def frame_statistics(priors: Mapping[str, np.ndarray], box: tuple[int, int, int, int] | None = None,
                     raw: np.ndarray | None = None, bit_depth: int | None = None, stride: int = 1) -> FrameStatistics:
    """Statistics of one frame's priors (``model.priors.compute_priors`` output with "intensity" and "dolp", at
    the mosaic's resolution) over ``box`` (top, left, height, width; default the centre square).

    ``stride``: the levels read every ``stride``-th pixel of every ``stride``-th row of the box (the station reads a
    ninth: ``station.inspector.Inspector.STATS_STRIDE``); ``edge_level`` always reads its own anchors
    (``EDGE_STRIDE``), so it comes out the same at any ``stride``.
    Clipped share, best source first: the ``raw`` mosaic's codes at full scale (``bit_depth``, default the dtype's)
    in the box; a ``Priors`` result's saturation count over the whole frame; intensity >= ``CLIP_LEVEL``."""
    inten = np.asarray(priors["intensity"], dtype=np.float32)
    top, left, h, w = box = box if box is not None else centre_square(*inten.shape)
    sampled = (slice(top, top + h, stride), slice(left, left + w, stride))  # the box, every stride-th pixel
    region = inten[sampled]
    dark, median, high = (float(v) for v in np.percentile(region, (DARK_PERCENTILE, 50, 95)))
    n_sat = getattr(priors, "n_saturated", None)
    if raw is not None:
        full = 2 ** (bit_depth or raw.dtype.itemsize * 8) - 1
        patch = raw[sampled]
        clipped = float(np.count_nonzero(patch >= full)) / max(patch.size, 1)
    elif n_sat is not None:
        clipped = float(n_sat) / inten.size  # mosaic and full-resolution priors have the same pixel count
    else:
        clipped = float(np.count_nonzero(region >= CLIP_LEVEL)) / max(region.size, 1)
    dolp = float(np.median(np.asarray(priors["dolp"])[sampled])) if "dolp" in priors else 0.0
    return FrameStatistics(median, high, min(clipped, 1.0), dolp, dark, edge_level(inten, box))


def edge_level(intensity: np.ndarray, box: tuple[int, int, int, int] | None = None) -> float:
    """How sharp the frame is: the ``EDGE_PERCENTILE`` of the intensity's steps over the 95th percentile of the
    intensity at the same anchors (the region's highlight level), so an exposure change does not move it.
    ``intensity``: the unpolarized intensity at the mosaic's resolution (full-scale units, finite); ``box``: (top,
    left, height, width), default the centre square. A step is the larger of the differences to the right and the
    lower neighbour ``d`` = max(1, round(side / ``EDGE_SCALE``)) px away (1 px on the renders), taken at anchors every
    ``EDGE_STRIDE`` steps: about 25,000 anchors on any frame, so the value does not depend on how the other
    statistics were sampled and costs the same on a large sensor.

    A lens blur of sigma s (steps) lowers a sharp edge's step to about erf(0.5 / (sqrt(2) s)) of the edge's height
    (0.38 at 1, 0.26 at 1.5), and a moving part lowers it along its motion; an exposure change scales the steps and
    the highlight level alike. 0 for a frame with no light."""
    inten = np.asarray(intensity, dtype=np.float32)
    top, left, h, w = box if box is not None else centre_square(*inten.shape)
    d = max(1, round(min(h, w) / EDGE_SCALE))
    if h <= d or w <= d:
        return 0.0
    k = EDGE_STRIDE * d
    here = inten[top:top + h - d:k, left:left + w - d:k]
    right = inten[top:top + h - d:k, left + d:left + w:k]
    down = inten[top + d:top + h:k, left:left + w - d:k]
    steps = np.maximum(np.abs(right - here), np.abs(down - here))
    high = float(np.percentile(here, 95))
    return float(np.percentile(steps, EDGE_PERCENTILE)) / high if high > 0 else 0.0


@dataclass(frozen=True)
class StatisticsRange:
    """What a model was trained on: per statistic the 2nd, 25th, 50th, 75th and 98th percentile over its frames
    (``low``, ``q1``, ``median``, ``q3``, ``high``), and the number of frames. Stored in the model's sidecar
    (``to_dict``). Single frames vary widely (part colour, light, pose); the median of a window of frames stays
    near the middle quartiles, which is what a drift check compares with."""

    low: dict[str, float]
    q1: dict[str, float]
    median: dict[str, float]
    q3: dict[str, float]
    high: dict[str, float]
    n_frames: int

    PERCENTILES = (2.0, 25.0, 50.0, 75.0, 98.0)
    KEYS = ("low", "q1", "median", "q3", "high")

    @classmethod
    def from_frames(cls, stats: Iterable[FrameStatistics]) -> StatisticsRange:
        rows = [s.as_dict() for s in stats]
        if not rows:
            raise ValueError("a statistics range needs at least one frame")
        out: dict[str, dict[str, float]] = {k: {} for k in cls.KEYS}
        for name in (n for n in STAT_NAMES if all(r[n] is not None for r in rows)):
            values = np.percentile(np.array([r[name] for r in rows], dtype=np.float64), cls.PERCENTILES)
            for key, v in zip(cls.KEYS, values, strict=True):
                out[key][name] = float(v)
        return cls(**out, n_frames=len(rows))

    def to_dict(self) -> dict:
        return {**{k: getattr(self, k) for k in self.KEYS}, "n_frames": self.n_frames,
                "percentiles": list(self.PERCENTILES), "region": "centre square"}

    @classmethod
    def from_dict(cls, d: Mapping) -> StatisticsRange:
        return cls(**{k: {n: float(v) for n, v in d[k].items()} for k in cls.KEYS}, n_frames=int(d.get("n_frames", 0)))

    def describe(self) -> str:
        return ", ".join(f"{k} {self.median[k]:.3f} (quartiles {self.q1[k]:.3f}..{self.q3[k]:.3f}, frames "
                         f"{self.low[k]:.3f}..{self.high[k]:.3f})" for k in STAT_NAMES if k in self.median)
