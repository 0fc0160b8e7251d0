"""Photometric stereo with a segmented dome: the priors of one part imaged once per dome segment, lit in turn.

Convention (``CONVENTION_VERSION`` unchanged: frame sets are new, single frames read as before):
    segments   azimuths in degrees of each frame's lit side, from world +x toward +y (``sim.scene``'s
               ``ambient_gradient_azimuth_deg``; image right is +x on the line presets), in the order the frames
               were taken; ``DOME_PAIRS`` names the opposite pairs a tilt is read from
    uniform    the mean of the frames' Stokes vectors (S0, S1, S2): light adds, so the mean over segments that
               cover the dome is the frame under the whole dome; intensity, DoLP and AoLP come from it as from
               one frame (``model.priors.api.priors_from_stokes``)
    tilt       ``(I_a - I_b) / (I_a + I_b)`` of a pair's frames (a, b opposite, I = S0 / 2), in [-1, 1]: the
               surface's tilt toward segment a. Albedo, colour, exposure and gain are a factor on both frames
               and divide out; 0 where both frames are dark (``DARK_S0``), so never NaN or Inf. Measured on
               renders (docs/results/2026-11-25-photometric-stereo.md): under a dome 9x brighter on its lit side
               than on the other (``ambient_gradient`` 0.8) a 3 deg dent flank moves it by about 0.03
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache

import cv2
import numpy as np

from .conventions import DARK_S0

DOME_PAIRS: dict[str, tuple[float, float]] = {"tilt_x": (0.0, 180.0), "tilt_y": (90.0, 270.0)}
"""Tilt prior -> the azimuths (degrees) of the frames it compares: toward +x (0) against -x (180), toward +y (90)
against -y (270)."""


MOTION_WIDTH_PX = 640
"""Frames are compared for motion at most this wide (``frame_motion``; wider ones binned n x n): about 9 ms per pair
at 640 x 480 on these 2 cores. The whole frame, not its middle: on the middle alone, two frames of a still part read
up to 0.7 px (stray light that differs between them fills more of it); on the whole frame at most 0.19 px."""

MAX_MOTION = 0.5 / 640
"""The most a part may move between the frames of its set, as a fraction of the frame's width (0.5 px on a 640 px
frame). The tilt compares each pixel across frames, so motion reads as tilt at every edge: measured with the
rule-23 tilt model on 60 good validation parts (docs/results/2026-11-27-frame-sets.md), a shift of 0.25 px rejected
2 % of them (as many as with none), 0.5 px 12 %, 1 px 98 %."""

MIN_MOTION_PX = 0.35
"""The limit is never below this (frames narrower than 448 px): about twice what ``frame_motion`` reads for two frames
of a still part, good or defective (at most 0.19 px over the 200 validation parts of the rule-23 sets)."""


def motion_limit(width: int) -> float:
    """The most a part may move between its frames (px) on frames ``width`` px wide: ``MAX_MOTION`` of the width,
    at least ``MIN_MOTION_PX``."""
    return max(MAX_MOTION * width, MIN_MOTION_PX)


def tilt(s0_a: np.ndarray, s0_b: np.ndarray) -> np.ndarray:
    """``(S0_a - S0_b) / (S0_a + S0_b)`` (the same ratio of intensities), float32 in [-1, 1]; 0 where the sum is
    at or below ``2 * DARK_S0`` or not finite."""
    a = np.asarray(s0_a, dtype=np.float32)
    b = np.asarray(s0_b, dtype=np.float32)
    total = a + b
    ok = np.isfinite(total) & (total > 2 * DARK_S0)
    out = np.divide(a - b, total, out=np.zeros_like(total), where=ok)
    return np.clip(np.nan_to_num(out, nan=0.0, posinf=0.0, neginf=0.0), -1.0, 1.0).astype(np.float32)


def frames_per_part(segments: Sequence[float] | None) -> int:
    """The frames one part is imaged in: one per segment, or one under the whole dome (no segments)."""
    return max(1, len(segments or ()))


def check_segments(segments: Sequence[float]) -> tuple[float, ...]:
    """``segments`` as floats; ValueError unless they are two or more distinct azimuths in [0, 360) degrees, or none
    (one frame per part, under the whole dome)."""
    segs = tuple(float(a) for a in segments)
    if segs and (len(segs) < 2 or len(set(segs)) != len(segs) or not all(0 <= a < 360 for a in segs)):
        raise ValueError(f"{list(segs)}: two or more distinct azimuths in [0, 360) degrees, one per frame")
    return segs


def same_segments(a: Sequence[float], b: Sequence[float]) -> bool:
    """Whether two lists of azimuths name the same segments in the same order (to 0.01 deg, modulo 360)."""
    return len(a) == len(b) and all(segment_index([x], y) == 0 for x, y in zip(a, b, strict=True))


@lru_cache(maxsize=4)
def _window(shape: tuple[int, int]) -> np.ndarray:
    return cv2.createHanningWindow((shape[1], shape[0]), cv2.CV_32F)


def frame_motion(s0_a: np.ndarray, s0_b: np.ndarray) -> float:
    """How far (px of these frames, any direction) the scene moved from frame a to frame b: phase correlation of
    their S0, binned to at most ``MOTION_WIDTH_PX`` wide. The segments' different light is a low-frequency change that
    hardly moves it: two frames of a still part read 0.0-0.2 px at 640 px (rendered sets), a 1 px shift 0.9-1.2 px.
    0.0 when a frame is flat or not finite (nothing to align; never NaN)."""
    if np.shape(s0_a) != np.shape(s0_b) or np.ndim(s0_a) != 2 or min(np.shape(s0_a)) < 16:
        return 0.0
    a, b = (np.nan_to_num(np.asarray(x, dtype=np.float32), nan=0.0, posinf=0.0, neginf=0.0) for x in (s0_a, s0_b))
    if not (a.std() > 1e-6 and b.std() > 1e-6):
        return 0.0
    n = math.ceil(a.shape[1] / MOTION_WIDTH_PX)  # binned n x n: a resize by another factor misreads shifts
    if n > 1:
        a, b = (x[: x.shape[0] // n * n, : x.shape[1] // n * n].reshape(x.shape[0] // n, n, x.shape[1] // n, n)
                .mean((1, 3)) for x in (a, b))
    (dx, dy), _ = cv2.phaseCorrelate(a, b, _window(a.shape))
    moved = n * math.hypot(dx, dy)
    return moved if math.isfinite(moved) else 0.0


def segment_index(segments: Sequence[float], azimuth: float) -> int | None:
    """Position of ``azimuth`` (degrees) in ``segments`` (to 0.01 deg, modulo 360), None when not imaged."""
    for k, a in enumerate(segments):
        if abs((float(a) - azimuth + 180.0) % 360.0 - 180.0) < 0.01:
            return k
    return None


def describe_segments(segments: Sequence[float]) -> str:
    """``(0.0, 180.0)`` -> "a frame per dome segment at 0, 180 deg"; () -> "one frame per part" (for messages)."""
    return f"a frame per dome segment at {', '.join(f'{a:g}' for a in segments)} deg" if segments else \
        "one frame per part"


def check_tilts(names: Sequence[str], segments: Sequence[float]) -> None:
    """ValueError naming the tilt priors in ``names`` that ``segments`` cannot give (a pair's frame missing)."""
    missing = [n for n in names if n in DOME_PAIRS
               and any(segment_index(segments, a) is None for a in DOME_PAIRS[n])]
    if missing:
        need = "; ".join(f"{n} needs frames at {DOME_PAIRS[n][0]:g} and {DOME_PAIRS[n][1]:g} deg" for n in missing)
        raise ValueError(f"{need}; there is {describe_segments(segments)}")


def mean_stokes(stokes: Sequence[tuple[np.ndarray, np.ndarray | None, np.ndarray | None]]
                ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
    """The uniform dome's (S0, S1, S2): the mean of the frames' (S1, S2 None when a frame lacks them); one frame's
    own arrays, not copied."""
    if not stokes:
        raise ValueError("no frames")
    if len(stokes) == 1:
        return stokes[0][0], stokes[0][1], stokes[0][2]
    s0 = np.mean([s[0] for s in stokes], 0, dtype=np.float32)
    if any(s[1] is None or s[2] is None for s in stokes):
        return s0, None, None
    return (s0, np.mean([s[1] for s in stokes], 0, dtype=np.float32),
            np.mean([s[2] for s in stokes], 0, dtype=np.float32))


def tilt_maps(names: Sequence[str], segments: Sequence[float], s0s: Sequence[np.ndarray]) -> dict[str, np.ndarray]:
    """The tilt priors among ``names`` from each frame's S0 (``segments`` order); ValueError when a pair's frame
    is missing (``check_tilts``)."""
    check_tilts(names, segments)
    out = {}
    for n in names:
        if n in DOME_PAIRS:
            a, b = (segment_index(segments, az) for az in DOME_PAIRS[n])
            assert a is not None and b is not None
            out[n] = tilt(s0s[a], s0s[b])
    return out
