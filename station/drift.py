"""Drift of the live frames away from what the model was trained on: a rolling window of
``model.priors.frame_stats.FrameStatistics`` against the ``StatisticsRange`` recorded in the model's sidecar
(``train.frame_statistics``, written by ``station train`` and ``station adapt``), with a warning that says which
camera setting to turn. ``station run`` (``station.loop.Station``) updates it with every judged part in view, logs
the text it returns, keeps the warning in force in each row's ``drift`` column and shows it in the viewer. Beside it,
``ViewMonitor`` watches how many parts lay partly outside the model's view, and ``TurnMonitor`` how far the parts lie
turned from the model's good parts (both: a camera turned from square), and ``LookMonitor`` how the look network
reads the good parts (a lens unlike the renders'), warned alike. ``CameraWatch`` holds one
camera's monitors: a station with a second camera watches its drift against its own model too, its warnings named for
it."""

from __future__ import annotations

from collections import deque
from collections.abc import Mapping
from typing import Any

import numpy as np

from model.draem.frame_checks import UNSEEN_LIMIT
from model.priors.frame_stats import STAT_NAMES, FrameStatistics, StatisticsRange

TOLERANCE_FLOOR = {"median_level": 0.01, "high_level": 0.01, "clipped_fraction": 0.002, "dolp_level": 0.01,
                   "dark_level": 0.005, "edge_level": 0.005}
"""Smallest tolerance per statistic (full-scale units or shares): a model trained on near-identical frames must
not warn at every noise flicker."""

TONE = ("; or the camera applies a gamma or look-up table the station could not turn off (an Aravis camera is "
        "set Gamma 1, GammaEnable and LUTEnable off where it has them): look for its vendor's own tone feature")
"""Said with every level's advice: a camera's tone curve moves the levels unevenly, as a black level, an exposure or
noise would (docs/results/2026-12-04-gamma.md: a gamma of 0.8 read as a black level and cost 5 points of defects)."""

ADVICE = {
    ("median_level", "low"): ("frames darker than trained: raise [camera] exposure_us (or gain_db), check the light"
                              + TONE),
    ("median_level", "high"): ("frames brighter than trained: lower [camera] exposure_us (or gain_db); if exposure "
                               "and gain are as trained, the camera adds a black level the station is not told: "
                               "measure it (station defect-pixels) and set [camera] black_level" + TONE),
    ("high_level", "low"): "highlights darker than trained: raise exposure_us, check the light" + TONE,
    ("high_level", "high"): "highlights brighter than trained: lower exposure_us (or gain_db)" + TONE,
    ("clipped_fraction", "high"): "more clipped pixels than trained: lower exposure_us or gain_db",
    ("clipped_fraction", "low"): "fewer clipped pixels than trained",
    ("dolp_level", "low"): "polarization lower than trained: light, belt or lens changed; re-adapt (station adapt)",
    ("dolp_level", "high"): "polarization higher than trained: light, belt or lens changed; re-adapt (station adapt)",
    ("dark_level", "high"): ("darkest pixels brighter than trained: the camera adds a black level the station is not "
                             "told (measure it: station defect-pixels; set [camera] black_level), or stray light "
                             "fills the shadows" + TONE),
    ("dark_level", "low"): ("darkest pixels darker than trained: [camera] black_level set above the camera's, or the "
                            "light dimmed" + TONE),
    ("edge_level", "low"): ("frames softer than trained: check the lens's focus and that the lens is clean (dust, a "
                            "film, condensation); a part moving during the exposure softens them too: shorten "
                            "[camera] exposure_us"),
    ("edge_level", "high"): ("frames sharper or noisier than trained: more gain_db or less light adds noise; a lens "
                             "focused since the model's frames were taken: re-adapt (station adapt)" + TONE),
}


def trained_range(meta: Mapping[str, Any]) -> StatisticsRange | None:
    """The frame statistics a checkpoint's sidecar records (None for models from before they were recorded)."""
    d = (meta.get("train") or {}).get("frame_statistics")
    return StatisticsRange.from_dict(d) if d else None


class DriftMonitor:
    """Rolling ``window`` of frames; once ``min_frames`` are in, the window's median of each statistic is compared
    with the trained frames' quartiles widened by ``margin`` times the interquartile range (at least
    ``TOLERANCE_FLOOR``): the median of 20 frames like the trained ones leaves their quartiles in about 3 % of
    windows, and leaves them widened by half the interquartile range far more rarely. ``update`` returns a warning
    text when the window leaves the range and when another statistic leaves it during the same excursion (a statistic
    that comes back and leaves again is not said twice), and a note when every statistic is back; ``warning`` is the
    current state's text (None in range). ``section``: the station.toml table of the camera watched, named in the
    advice ("[camera] exposure_us"; "second_camera" for the second camera's)."""

    def __init__(self, trained: StatisticsRange, window: int = 50, min_frames: int = 10, margin: float = 0.5,
                 section: str = "camera"):
        if window < 1 or not 1 <= min_frames <= window:
            raise ValueError(f"drift monitor: need 1 <= min_frames <= window, got {min_frames}, {window}")
        self.trained = trained
        self.section = section
        self.window: deque[FrameStatistics] = deque(maxlen=window)
        self.min_frames = min_frames
        self.margin = margin
        self.warning: str | None = None
        self._said: set[tuple[str, str]] = set()

    def bounds(self, name: str) -> tuple[float, float]:
        lo, hi = self.trained.q1[name], self.trained.q3[name]
        tol = max(self.margin * (hi - lo), TOLERANCE_FLOOR.get(name, 0.0))
        return lo - tol, hi + tol

    def outside(self) -> list[tuple[str, str, float]]:
        """(statistic, "low"|"high", window median) for every statistic outside its bounds."""
        if len(self.window) < self.min_frames:
            return []
        out = []
        for name in STAT_NAMES:
            if name not in self.trained.median:
                continue
            med = float(np.median([getattr(s, name) for s in self.window]))
            lo, hi = self.bounds(name)
            if med < lo or med > hi:
                out.append((name, "low" if med < lo else "high", med))
        return out

    def advice(self, name: str, side: str) -> str:
        """What to turn when ``name`` is ``side`` ("low"|"high"): ``ADVICE``, its camera keys in this camera's table."""
        return ADVICE[(name, side)].replace("[camera]", f"[{self.section}]")

    def update(self, stats: FrameStatistics) -> str | None:
        self.window.append(stats)
        out = self.outside()
        if out:
            text = "; ".join(f"{name} {med:.3f} outside trained {self.trained.q1[name]:.3f}.."
                             f"{self.trained.q3[name]:.3f} ({self.advice(name, side)})" for name, side, med in out)
            text = f"drift over the last {len(self.window)} frames: {text}"
            new = [o[:2] for o in out if o[:2] not in self._said]  # a statistic newly out in this excursion
            self.warning = text
            self._said |= set(new)
            return text if new else None
        if self.warning is not None:
            self.warning = None
            self._said.clear()
            return f"frames back in the trained range over the last {len(self.window)} frames"
        return None


VIEW_WARN_SHARE = 0.05
"""Share of the parts with some of the part outside the model's view (``unseen_fraction`` over ``UNSEEN_LIMIT``)
above which the station and ``station report`` warn: on development sets 0.7 % and 1.7 % of a square line's parts had
some, 1.0 % and 3.0 % of lines turned 2 and 3 degrees (where no more good parts were rejected than square), 8.0 %
turned 4 degrees (2 more of 134 rejected), 10.8 % of a line turned 5 degrees
(docs/results/2026-12-05-outside-view.md)."""
VIEW_WINDOW = 200
"""Parts the station's share is taken over. A share is a count of few parts, so the window must be long enough that a
square line's chance clusters stay under the share: over 5 % of 200 parts (11 or more) happens by chance in 0.07 % of
windows of a line at 1.7 %, 4.0 % at 3 %, and is reached in 93 % of windows of a line turned 4 degrees (8 %),
99.7 % turned 5 (binomial; docs/results/2026-12-06-view-window.md). A window of 50 warned on 5 % of a square line's
windows."""
VIEW_WARN_MIN_PARTS = 100
"""Parts needed before the share is judged, by the station and by ``station report``: at 100, over 5 % (6 or more)
happens by chance in 0.7 % of a line at 1.7 %, and is reached in 82 % of lines turned 4 degrees."""
VIEW_ADVICE = ("the camera turned from square to the belt or parts off their place: mount the camera square "
               "(docs/bring-up.md)")


def too_many_outside(outside: int, parts: int) -> bool:
    """Whether ``outside`` of ``parts`` judged parts lying partly outside the model's view call for the view warning:
    over ``VIEW_WARN_SHARE`` of at least ``VIEW_WARN_MIN_PARTS`` (``ViewMonitor``, ``station report``)."""
    return parts >= VIEW_WARN_MIN_PARTS and outside > VIEW_WARN_SHARE * parts


class PartsWarning:
    """A rolling ``window`` of one value per judged part (at least ``min_parts`` long) and the warning it calls for:
    ``warning`` is the text in force (None while none is). ``said`` keeps it: it returns the text when a warning
    starts and the ``back`` note when it ends (each said once), None otherwise."""

    def __init__(self, window: int, min_parts: int, name: str) -> None:
        if window < min_parts:
            raise ValueError(f"{name} monitor: need a window of at least {min_parts} parts, got {window}")
        self.window: deque = deque(maxlen=window)
        self.warning: str | None = None

    def said(self, warning: str | None, back: str) -> str | None:
        if warning is not None:
            started = self.warning is None
            self.warning = warning
            return warning if started else None
        if self.warning is not None:
            self.warning = None
            return back
        return None


class ViewMonitor(PartsWarning):
    """Rolling ``window`` of judged parts' ``unseen_fraction``; once ``VIEW_WARN_MIN_PARTS`` are in, ``update`` returns
    a warning when over ``VIEW_WARN_SHARE`` of them lay partly outside the model's view, and a note when the share is
    back under it; ``warning`` is the current state's text (None while under)."""

    def __init__(self, window: int = VIEW_WINDOW) -> None:
        super().__init__(window, VIEW_WARN_MIN_PARTS, "view")

    def update(self, unseen_fraction: float) -> str | None:
        self.window.append(unseen_fraction > UNSEEN_LIMIT)
        n, k = len(self.window), sum(self.window)
        warning = (f"view: {k} of the last {n} parts lay partly outside the model's view as registered (over "
                   f"{100 * VIEW_WARN_SHARE:g} %): {VIEW_ADVICE}") if too_many_outside(k, n) else None
        return self.said(warning, f"parts back in the model's view over the last {n} parts")


TURN_WARN_DEG = 5.0
"""Median ``turn_deg`` (degrees) of the recent parts beyond +-this: the parts lie turned from the model's good parts,
the camera turned from square to the belt or the fixture turning them. A camera turned t degrees moves every part's
turn by about -t (seeds 1217-1221: -2.8 to -11.6 at 3-12 degrees); the good parts of the line as built spread +-5.6
degrees about their median, whose median over 50 parts is within about 0.5 degree of it. The shipped file rejected as
many good parts turned 3-20 degrees one way as square, 21 of 180 turned 25, and 6 of 175 turned 12 the other way
(``frame_checks.TURN_LIMIT_DEG``; docs/results/2026-12-06-turn-check.md): a median beyond 5 degrees is a camera to
square before it costs parts."""
TURN_WINDOW = 100
"""Parts the station's median turn is taken over."""
TURN_WARN_MIN_PARTS = 50
"""Parts needed before the median turn is judged, by the station and by ``station report``."""
TURN_ADVICE = ("the camera turned from square to the belt or the fixture turning the parts: mount the camera square "
               "(docs/bring-up.md)")


def line_turn(turns: list[float]) -> float | None:
    """The median of judged parts' ``turn_deg`` (degrees) when it calls for the turn warning: at least
    ``TURN_WARN_MIN_PARTS`` of them and beyond +-``TURN_WARN_DEG`` (``TurnMonitor``, ``station report``); else None."""
    if len(turns) < TURN_WARN_MIN_PARTS:
        return None
    median = float(np.median(turns))
    return median if abs(median) > TURN_WARN_DEG else None


class TurnMonitor(PartsWarning):
    """Rolling ``window`` of judged parts' ``turn_deg``; once ``TURN_WARN_MIN_PARTS`` are in, ``update`` returns a
    warning when their median lies beyond +-``TURN_WARN_DEG``, and a note when it is back within; ``warning`` is the
    current state's text (None while within)."""

    def __init__(self, window: int = TURN_WINDOW) -> None:
        super().__init__(window, TURN_WARN_MIN_PARTS, "turn")

    def update(self, turn_deg: float) -> str | None:
        self.window.append(turn_deg)
        n, median = len(self.window), line_turn(list(self.window))
        warning = None if median is None else (
            f"turn: the last {n} parts lay turned {median:+.1f} degrees from the model's good parts at the median "
            f"(beyond {TURN_WARN_DEG:g}): {TURN_ADVICE}")
        return self.said(warning, f"parts back within {TURN_WARN_DEG:g} degrees of the model's good parts' turn over "
                                  f"the last {n} parts")


LOOK_WARN_LEVEL = 0.4
"""Median ``look_level`` (the look network's finding over its blend threshold) of the recent parts above this: the
network reads the line's frames as unlike its renders, most likely the lens (vignetting, focus), and at the file's
threshold more good parts are rejected than the validation promised. The
shipped file's good parts read 0.27 at the median on its validation set and on fresh seed 1240; the median of 100
parts of a line with up to a fifth of them defective stays within 0.25-0.33 there (99 % of draws), and reaches 0.46-0.67
through a lens keeping 80 % of the light at the frame's corners, where the file rejected 7 of 146 good parts against 4
as built (docs/results/2026-12-07-blend-otherwise.md, findings.py). A line with more defective parts reads higher."""
LOOK_WINDOW = 100
"""Parts the station's median look level is taken over."""
LOOK_WARN_MIN_PARTS = 50
"""Parts needed before the median look level is judged, by the station and by ``station report``."""
LOOK_ADVICE = ("the look network reads these frames as unlike its renders (a lens's vignetting or focus, another "
               "camera): adapt on the line's good parts through its own lens (station adapt, docs/bring-up.md step 6)")


def line_look(levels: list[float]) -> float | None:
    """The median of judged parts' ``look_level`` when it calls for the look warning: at least
    ``LOOK_WARN_MIN_PARTS`` of them and above ``LOOK_WARN_LEVEL`` (``LookMonitor``, ``station report``); else None."""
    if len(levels) < LOOK_WARN_MIN_PARTS:
        return None
    median = float(np.median(levels))
    return median if median > LOOK_WARN_LEVEL else None


class LookMonitor(PartsWarning):
    """Rolling ``window`` of judged parts' ``look_level`` (a file that blends its look network); once
    ``LOOK_WARN_MIN_PARTS`` are in, ``update`` returns a warning when their median lies above ``LOOK_WARN_LEVEL``, and
    a note when it is back under; ``warning`` is the current state's text (None while under)."""

    def __init__(self, window: int = LOOK_WINDOW) -> None:
        super().__init__(window, LOOK_WARN_MIN_PARTS, "look")

    def update(self, look_level: float) -> str | None:
        self.window.append(look_level)
        n, median = len(self.window), line_look(list(self.window))
        warning = None if median is None else (
            f"look: the last {n} parts' look level is {median:.2f} at the median (above {LOOK_WARN_LEVEL:g}): "
            f"{LOOK_ADVICE}")
        return self.said(warning, f"look level back under {LOOK_WARN_LEVEL:g} over the last {n} parts")


class CameraWatch:
    """One camera's monitors: its drift against its model's trained frames (``drift``; None when the model records
    none), how far its parts lie turned from its model's good parts (``turn``: parts whose model reads no turn give
    none), how its look network reads them (``look``: a file that blends, ``LookMonitor``) and, with ``view``, how
    many of its parts lay partly outside its model's view. ``name``: the camera's name
    put before each text (None for the first camera, whose texts stand as they are). The station watches the second
    camera's drift but not its view: ``VIEW_WARN_SHARE`` was read off the line camera's sets, and a camera looking
    level at the part has more on a square line (4-6 of 60 parts with a small side file: it would warn on every
    two-camera line, which would teach the line to ignore it; docs/results/2026-12-06-side-drift.md)."""

    def __init__(self, drift: DriftMonitor | None, name: str | None = None, view: bool = True) -> None:
        self.drift, self.view, self.name = drift, ViewMonitor() if view else None, name
        self.turn, self.look = TurnMonitor(), LookMonitor()

    def update(self, stats: FrameStatistics | None, checks: Mapping[str, float]) -> list[str]:
        """A judged part in view: its frame's statistics (None when not computed) and its model's frame checks ->
        the texts to log now (a warning starting or ending), each named for the camera."""
        said = []
        if self.drift is not None and stats is not None:
            said.append(self.drift.update(stats))
        if self.view is not None and "unseen_fraction" in checks:
            said.append(self.view.update(checks["unseen_fraction"]))
        if "turn_deg" in checks:
            said.append(self.turn.update(checks["turn_deg"]))
        if "look_level" in checks:
            said.append(self.look.update(checks["look_level"]))
        return [self._named(t) for t in said if t]

    @property
    def warning(self) -> str | None:
        """The warnings in force, "; "-joined and named for the camera; None when none is."""
        ws = [w for w in (m.warning for m in (self.drift, self.view, self.turn, self.look) if m is not None) if w]
        return "; ".join(self._named(w) for w in ws) or None

    def _named(self, text: str) -> str:
        return text if self.name is None else f"{self.name}: {text}"
