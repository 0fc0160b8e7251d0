"""One part's frame -> score and heatmap: demosaic, the priors the detector needs (and no others), the detector.

A model that reads a frame per dome segment (photometric stereo, ``model.priors.photometric``) gets the part's
frames in the segments' order: intensity and polarization from their mean Stokes, the tilts from opposite pairs, by
the functions ``model.priors.api.compute_set_priors`` uses for training and evaluation. The tilt compares each pixel
across the frames, so a part that moved between them reads as tilted at every edge and scores high: when the model
finds a part over its threshold, the inspector measures that motion (``model.priors.photometric.frame_motion``, about
10 ms a pair, paid by rejected parts only) and, beyond ``motion_limit``, gives it as the error, so the row says why.

With a presence check (``station.presence``), it runs on the priors before the detector; a frame with no part
in view comes back with ``present`` False and no score: the detector does not run. Its priors (DoLP) are
computed even when the detector does not read them; the check's own time is the "presence" stage.

Every stage is timed. Errors do not escape: they come back in ``Inspection.error`` so the loop can reject the
part with its reason (fail closed) and keep running.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from drivers.frame import Frame
from model.priors import MosaicLayout
from model.priors.api import check_prior_names, needs_polarization, set_priors_from_stokes, set_stokes
from model.priors.frame_stats import FrameStatistics, frame_statistics
from model.priors.photometric import check_tilts, describe_segments, frame_motion, frames_per_part, motion_limit
from model.priors.sensor_correction import SensorCorrection
from station.presence import Presence, PresenceCheck

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Inference:
    """A detector's answer: image score in [0, 1] and per-pixel anomaly probability (H', W') in [0, 1]; ``checks``:
    what the model's frame checks found (``model.draem.detector.DetectorOutput.frame_checks``; the log keeps
    ``model.draem.frame_checks.FRAME_CHECKS`` of them)."""

    score: float
    heatmap: np.ndarray | None = None
    checks: Mapping[str, float] = field(default_factory=dict)


class Detector(Protocol):
    """What the station needs from a model (``model`` provides it; tests use small fakes)."""

    model_id: str
    threshold: float
    priors: tuple[str, ...]
    """Names from ``model.priors.PRIOR_KEYS`` the detector reads; nothing else is computed."""

    def infer(self, priors: Mapping[str, np.ndarray]) -> Inference: ...


def significant_bits(frame: Frame, bit_depth: int | None) -> int:
    """The bits of ``frame``'s codes that carry the signal: ``bit_depth`` (``[priors] bit_depth``, for a pixel format
    wider than its codes, such as Mono16 carrying 12-bit codes) or the frame's own; ValueError naming the key when it
    asks for more bits than the frame has."""
    if bit_depth is None:
        return frame.bit_depth
    if bit_depth > frame.bit_depth:
        raise ValueError(f"[priors] bit_depth {bit_depth} is more than the frame's {frame.bit_depth} bits "
                         f"({frame.pixel_format})")
    return bit_depth


@dataclass
class Inspection:
    score: float | None = None
    heatmap: np.ndarray | None = None
    priors: dict[str, np.ndarray] = field(default_factory=dict)
    invalid_fraction: float = 0.0
    n_saturated: int = 0
    error: str | None = None
    presence: Presence | None = None
    """The presence check's answer; None when there is no check (or the priors failed before it)."""
    frame_stats: FrameStatistics | None = None
    """Brightness and polarization of the frame (``model.priors.frame_stats``) when the inspector computes them."""
    timings_ms: dict[str, float] = field(default_factory=dict)
    checks: dict[str, float] = field(default_factory=dict)
    """The detector's frame checks (``Inference.checks``)."""
    second: Inspection | None = None
    """The second camera's inspection of the same part (``station.second_camera``); None with one camera."""

    @property
    def present(self) -> bool:
        """False only when the presence check found no part in view."""
        return self.presence is None or self.presence.present

    @property
    def empty_reason(self) -> str | None:
        """The presence check's reason when it found no part in view, else None (``station.decision.decide``'s
        ``empty``)."""
        return self.presence.reason if self.presence is not None and not self.presence.present else None


class Inspector:
    """Parts' frames -> ``Inspection``s for one detector, layout and demosaic method; ``segments``: the dome
    segments' azimuths (degrees) the detector's model reads a frame of each (``ModelConfig.dome_segments``; () for
    one frame per part)."""

    STATS_STRIDE = 3
    """Frame statistics read every 3rd pixel of every 3rd row: 0.9 ms instead of 6.4 ms on a 640 x 480 frame (odd,
    so the mosaic's clipped count still samples all four polarizer angles)."""

    def __init__(self, detector: Detector, layout: MosaicLayout, method: str = "bilinear",
                 display_priors: tuple[str, ...] = (), presence: PresenceCheck | None = None,
                 statistics: bool = False, bit_depth: int | None = None,
                 segments: Sequence[float] = (), defect_pixels: np.ndarray | None = None,
                 black_level: int = 0) -> None:
        self.detector = detector
        self.correction = SensorCorrection.of(black_level, defect_pixels)
        """``[camera] black_level`` and ``defect_pixels`` (the map listed once here), undone in every frame before the
        demosaic (``model.priors.sensor_correction``)."""
        self.bit_depth = bit_depth
        """``[priors] bit_depth``: significant bits of the codes when the pixel format's are wider (a Mono16 camera
        carrying 12-bit codes); None: the frame's own."""
        self.layout = layout
        self.method = method
        self.presence = presence
        self.statistics = statistics
        extra = (presence.priors if presence is not None else ()) + (("intensity", "dolp") if statistics else ())
        self.names = check_prior_names(tuple(dict.fromkeys(detector.priors + display_priors + extra)))
        self.segments = tuple(float(a) for a in segments)
        check_tilts(self.names, self.segments)
        self.polarization = needs_polarization(self.names)
        self.slow_priors_ms: float | None = None
        """Demosaic and priors time (ms) from which the first frame is named once, with the keys that help
        (``station.loop.SLOW_PRIORS_SHARE`` of the cycle, set by the station); None: never."""
        self._named_slow = False

    def inspect(self, frames: Frame | Sequence[Frame]) -> Inspection:
        """Judge one part: its frame, or its frames in the order of ``segments``."""
        frames = (frames,) if isinstance(frames, Frame) else tuple(frames)
        frame = frames[0]
        result = Inspection()
        t = time.perf_counter()
        try:
            if len(frames) != frames_per_part(self.segments):
                raise ValueError(f"{len(frames)} frame(s) for a model that reads {describe_segments(self.segments)}")
            bits = significant_bits(frame, self.bit_depth)
            raws = [self.correction(f.raw, bits) for f in frames]
            norms, stokes = set_stokes(raws, self.layout, self.method, self.polarization, bits)
            t_demosaic = time.perf_counter()
            result.timings_ms["demosaic"] = 1e3 * (t_demosaic - t)
            result.priors = set_priors_from_stokes(self.names, self.segments, stokes)
            result.invalid_fraction = max(n.n_nonfinite + n.n_out_of_range for n in norms) / frame.raw.size
            result.n_saturated = max(n.n_saturated for n in norms)
            if self.statistics:
                result.frame_stats = frame_statistics({n: result.priors[n] for n in ("intensity", "dolp")},
                                                      raw=raws[0], bit_depth=bits, stride=self.STATS_STRIDE)
            t_priors = time.perf_counter()
            result.timings_ms["priors"] = 1e3 * (t_priors - t_demosaic)
            self._name_slow_priors(frame, 1e3 * (t_priors - t))
        except Exception as exc:  # any failure here is a part we cannot judge
            result.error = f"frame {frame.frame_id}: priors failed: {type(exc).__name__}: {exc}"
            return result
        if self.presence is not None:
            try:
                result.presence = self.presence(result.priors)
            except Exception as exc:  # no answer is not "empty": the part is rejected, not skipped
                result.error = f"frame {frame.frame_id}: presence check failed: {type(exc).__name__}: {exc}"
                return result
            t_check = time.perf_counter()
            result.timings_ms["presence"] = 1e3 * (t_check - t_priors)
            t_priors = t_check  # the model's time starts after the check
            if not result.present:
                return result  # nothing to judge: the model does not run
        try:
            inference = self.detector.infer(result.priors)
            result.score, result.heatmap = float(inference.score), inference.heatmap
            result.checks = dict(inference.checks)
        except Exception as exc:
            result.error = (f"frame {frame.frame_id}: model {self.detector.model_id} failed: "
                            f"{type(exc).__name__}: {exc}")
        if len(frames) > 1 and result.error is None and not result.score <= self.detector.threshold:
            result.error = self._moved(frames, stokes, result.score)  # why it scored high, when it moved
        result.timings_ms["model"] = 1e3 * (time.perf_counter() - t_priors)  # with the motion check
        return result

    def close(self) -> None:
        """Nothing to end: it runs on its caller's thread (``PairInspector.close``'s peer, called by the loop)."""

    @staticmethod
    def _moved(frames: Sequence[Frame], stokes: Sequence[tuple[np.ndarray, ...]], score: float) -> str | None:
        """Why a part that ``score``s high cannot be judged, when it moved between its frames by more than
        ``motion_limit``; else None."""
        limit = motion_limit(frames[0].width)
        for k in range(1, len(frames)):
            px = frame_motion(stokes[0][0], stokes[k][0])
            if px > limit:
                return (f"frame {frames[0].frame_id}: the part moved {px:.2f} px between frames 1 and {k + 1} of its "
                        f"set (at most {limit:.2f} px; score {score:.4f}, which the motion raises): it must stay "
                        "still while the dome's segments are lit in turn")
        return None

    def _name_slow_priors(self, frame: Frame, ms: float) -> None:
        """Warn once when a frame's demosaic and priors take ``slow_priors_ms`` or more: the parts are then rejected
        as late (at its deadline, before the model answers), and no row says why."""
        if self.slow_priors_ms is None or self._named_slow or ms < self.slow_priors_ms:
            return
        self._named_slow = True
        h, w = frame.raw.shape[:2]
        log.warning("demosaic and priors took %.0f ms on a %d x %d frame (%s): parts will be rejected as late; set "
                    "[priors] demosaic = \"superpixel\" or a smaller [camera] region (docs/bring-up.md, step 5)",
                    ms, w, h, self.method)
