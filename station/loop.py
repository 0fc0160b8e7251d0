"""The inspection loop: trigger -> grab -> demosaic -> priors -> model -> decision -> log -> PLC.

Acquisition runs in its own thread and hands parts to processing through a bounded ``FrameQueue`` with the
configured backpressure. A part's time counts from when its trigger reached the host. Every part the PLC announces
(or every frame, trigger-free) ends in exactly one log row, written before the PLC hears the decision
(write-ahead; ``RecordKeeper``), with ``io_delivered`` set once the PLC acknowledges it:

- judged: ``pass`` or ``reject`` (with the reason);
- could not be judged (no frame of its own after a trigger, lost camera, priors or model error, NaN score or
  threshold, over the cycle time, a trigger older than the cycle before acquisition took it, a row that could not
  be written): ``reject`` with the reason, and the PLC is told REJECT (fail closed);
- dropped by backpressure: ``not_inspected`` with the reason, and the PLC is told REJECT;
- no part in view (``station.presence``, before the model runs): ``empty`` with the check's value as reason,
  trigger-free, where an empty frame is the gap between parts: the PLC is told nothing and no image is kept. When
  the PLC announced a part (triggered), a part was expected and not seen (missing, misplaced, or a part the check
  cannot see), and an unseen part must never pass: ``reject`` with the check's reason, at the PLC and in the row.

With a second camera (``[second_camera]``: ``drivers.camera_pair``, ``station.second_camera``), each part's frame
carries the second camera's frame of it; the part is decided on both (``station.decision.join``) and still gets one
row and one answer.

``stop()`` (or SIGINT/SIGTERM through ``run_until_signal``) ends acquisition and drains the queue; then every
part announced until the PLC link closes is recorded and rejected ("station stopping"), the PLC's last
acknowledgements are awaited and recorded, and the link is closed. Rules and faults: docs/fail-closed.md.
"""

from __future__ import annotations

import contextlib
import dataclasses
import logging
import signal
import threading
import time
from collections import Counter, deque
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

import numpy as np

from drivers.camera import Camera
from drivers.errors import CameraError, CameraTimeout
from drivers.frame import Frame, GroundTruth
from drivers.line_io import Trigger
from model.draem.frame_checks import FRAME_CHECKS, beyond_limits
from station.config import frame_delay_limit_ms
from station.decision import Decision, Verdict, decide, join, late
from station.drift import CameraWatch, DriftMonitor
from station.frame_queue import Closed, FrameQueue
from station.heap import CollectorPauses, frozen_heap
from station.inspection_log import LOGGED_STATISTICS, InspectionLog, InspectionRecord
from station.inspector import Inspection, Inspector
from station.line_link import LineLink
from station.model_thread import ModelThread, NoAnswer
from station.records import RecordKeeper
from station.reject_store import RejectStore
from station.second_camera import SECOND_NAME, PairInspector
from station.viewer import ViewerFeed, ViewFrame

log = logging.getLogger(__name__)

MAX_LOST_ROWS = 10000
"""At most this many rows for one gap in frame ids (a camera reset can jump its counter by millions)."""

CLOCK_READS = 5
"""Attempts at reading the wall clock and ``time.perf_counter`` together (``perf_from_host_ns``)."""

CLOCK_PAIR_S = 0.0005
"""A pair of clock reads is trusted when the wall clock's two reads around ``perf_counter`` lie this close (s): a
thread preempted between them (a loaded machine) would otherwise shift a frame's time by the preemption. A frame
taken up to this long before its part's earliest time still counts as the part's (the pairing's error)."""

MAX_HELD_GAP = 16
"""Line trigger: the most frames that may go missing between two frames for the newer one to be kept for the part it
belongs to (``Station._grab_for``); a larger jump in frame ids (a reset or misread counter) cannot be matched to a
part, and the frame is dropped (its part rejected, the next parts resynchronise)."""

MAX_UNUSABLE_FRAMES = 50
"""Grabs in a row that may fail with something other than a timeout or a lost camera (a frame that cannot be decoded,
a trigger call that fails) before the station stops as for a lost camera: each such part is rejected with the error,
and a camera that delivers nothing usable must not keep the line running on rejects (or spin in free run)."""

MAX_MODEL_BUSY_PARTS = 50
"""Parts rejected as "model busy" while the model is still on one earlier part's frame (``station.model_thread``)
before the station stops as for a lost camera: a model that never returns must not keep the line running on rejects.
A model that is merely slower than the cycle answers between parts and never reaches this."""

COLLECTOR_PAUSE_SHARE = 0.25
"""Share of the cycle time a garbage collection may hold the station before the run's end warns of it (``station.heap``;
the run summary's ``collector_pause_max_ms`` gives the longest): the station freezes its heap at the start of a run so
that none should come near it."""

SLOW_PRIORS_SHARE = 0.5
"""Share of ``[acquisition] cycle_time_ms`` that a frame's demosaic and priors may take before the station warns once
(``Inspector.slow_priors_ms``), naming the keys that help: on the whole 2448 x 2048 sensor they take 95 ms of a
100 ms cycle on 2 cores with the bilinear demosaic (38 ms with superpixel; docs/results/2026-11-26-frame-shape.md).
Every part is then rejected as late, each row saying so but nothing saying why."""


class SetIncomplete(Exception):
    """A frame per dome segment (``[camera] dome_segments``): a frame after the first of a part's set did not come (the
    grab timed out); the part cannot be judged on fewer frames than the model reads."""


class FramesLost(Exception):
    """Line trigger: the part being grabbed has no frame: it was lost in transport (a gap in frame ids), or the camera
    never saw its pulse (the next frame was exposed too long after its TRIG)."""


def perf_from_host_ns(host_ns: int) -> float:
    """A host wall-clock time (``time.time_ns``, ns) on ``time.perf_counter``'s clock (s). The two clocks are read
    together, the wall clock before and after ``perf_counter``; the pair with the closest wall reads of up to
    ``CLOCK_READS`` is used, the first within ``CLOCK_PAIR_S`` at once. Its error is half that pair's spread."""
    best = None
    for _ in range(CLOCK_READS):
        before = time.time_ns()
        perf = time.perf_counter()
        after = time.time_ns()
        if best is None or after - before < best[0]:
            best = (after - before, perf - ((before + after) / 2 - host_ns) / 1e9)
        if after - before <= CLOCK_PAIR_S * 1e9:
            break
    return best[1]


def part_truth(frame: Frame | None) -> GroundTruth | None:
    """A simulated part's ground truth: its frame's, made defective when the second camera's frame of it
    (``Frame.companion``) shows a defect the first camera's does not (each rendered view's label says whether that
    camera sees the defect). None without ground truth."""
    gt = frame.ground_truth if frame is not None else None
    other = frame.companion.ground_truth if frame is not None and frame.companion is not None else None
    if gt is not None and other is not None and other.label and not gt.label:
        return dataclasses.replace(gt, label=1)
    return gt


class TransferClock:
    """Triggered frames: when a frame would have reached the host had its transfer been as quick as the quickest of
    the last ``WINDOW`` frames. It tells a frame taken late (a later part's, after a missed pulse) from one taken on
    time that came slowly (packet resends, a network stall), and a frame taken before a part's trigger from one taken
    after it. Uses the camera's timestamp (its own clock, in ns): the host time of a frame minus it is the clock
    offset plus that frame's transfer time; the smallest over recent frames is the offset plus the quickest transfer.
    Camera timestamps that go backwards (a reconnect resets the camera's clock) start over. The host's completion
    time is used as it is for a camera without timestamps (0), and for one whose clock does not run at the host's
    rate within ``MAX_RATE_ERROR`` over the window (a wrong tick frequency would shift every frame)."""

    WINDOW = 64
    MAX_RATE_ERROR = 0.01

    def __init__(self) -> None:
        self._seen: deque[tuple[float, float]] = deque(maxlen=self.WINDOW)  # (camera s, host completion s)
        self._last_ns = 0
        self.untrusted = False
        """The camera's clock did not keep the host's rate: its timestamps are not used."""

    def fastest(self, frame: Frame, completed: float) -> float:
        """``completed`` (``time.perf_counter()`` clock, s) less the part of the frame's transfer time above the
        quickest lately."""
        if frame.timestamp_ns <= 0:
            return completed
        if frame.timestamp_ns < self._last_ns:
            self._seen.clear()
        self._last_ns = frame.timestamp_ns
        camera_s = frame.timestamp_ns / 1e9
        self._seen.append((camera_s, completed))
        offsets = [h - c for c, h in self._seen]
        span = self._seen[-1][1] - self._seen[0][1]
        half = len(offsets) // 2
        # the quickest transfer is the same early and late in the window unless the clocks' rates differ (a slow
        # transfer raises one offset, never the smallest)
        if span > 2.0 and abs(min(offsets[half:]) - min(offsets[:half])) > self.MAX_RATE_ERROR * span / 2:
            if not self.untrusted:
                log.warning("camera timestamps drift from the host clock (%.0f ms over %.1f s): not used to time "
                            "frames", 1e3 * (min(offsets[half:]) - min(offsets[:half])), span)
            self.untrusted = True
        if self.untrusted:
            return completed
        return camera_s + min(offsets)


@dataclass
class Part:
    """A part between acquisition and processing."""

    part_id: str
    t_trigger: float
    """``time.perf_counter()`` when the part arrived: when its TRIG line reached the host (``Trigger.t_arrival``),
    or the grab's start when trigger-free. Every latency of the part counts from here."""
    frame: Frame | None = None
    frames: tuple[Frame, ...] = ()
    """All of the part's frames when it is imaged once per dome segment (``[camera] dome_segments``), the first being
    ``frame``; empty for one frame per part."""
    grab_ms: float | None = None
    error: str | None = None
    announced: bool = True
    """False for frames lost in transport: no PLC part id to answer."""
    late_ms: float | None = None
    """Set when the trigger was already older than the cycle time when acquisition took it (no frame taken)."""

    @property
    def taken(self) -> tuple[Frame, ...]:
        """Every frame taken for the part, in order: ``frames``, or ``frame`` alone."""
        return self.frames or ((self.frame,) if self.frame is not None else ())


@dataclass
class LiveStats:
    """Running statistics: counts per decision, confusion against ground truth, recent latencies.

    ``confusion`` keys are ``<truth>_<decision>``: truth "good", "bad" (a part, by its label) or "none" (no part
    in view); decision "pass", "reject" or "empty". So "none_empty" counts empty frames skipped, "good_empty" and
    "bad_empty" parts the presence check missed, "none_pass"/"none_reject" empty frames the model judged."""

    counts: Counter[str] = field(default_factory=Counter)
    confusion: Counter[str] = field(default_factory=Counter)
    latencies_ms: deque[float] = field(default_factory=lambda: deque(maxlen=1000))
    started: float = field(default_factory=time.perf_counter)

    def add(self, decision: Verdict, total_ms: float | None, truth: int | None, present: bool = True) -> None:
        """One part; ``truth``: its label where known (None: no ground truth), ``present``: whether the ground
        truth has a part in view."""
        self.counts[decision] += 1
        if total_ms is not None:
            self.latencies_ms.append(total_ms)
        if truth is not None and decision in (Verdict.PASS, Verdict.REJECT, Verdict.EMPTY):
            kind = "none" if not present else "bad" if truth else "good"
            self.confusion[f"{kind}_{decision}"] += 1

    def summary(self) -> dict[str, float]:
        n = sum(self.counts.values())
        lat = np.array(self.latencies_ms) if self.latencies_ms else np.zeros(1)
        return {"parts": n, "rejects": self.counts[Verdict.REJECT], "empty": self.counts[Verdict.EMPTY],
                "not_inspected": self.counts[Verdict.NOT_INSPECTED],
                "parts_per_s": n / max(time.perf_counter() - self.started, 1e-9),
                "p50_ms": float(np.percentile(lat, 50)), "p99_ms": float(np.percentile(lat, 99))}


class Station:
    """Runs the loop over one camera, inspector, PLC link and log (opened by the caller; ``run`` closes the link
    at its end, after the last announced part was answered). ``threshold``: reject when score > threshold; None
    (the station's own callers) takes the detector's, ``inspector.detector.threshold``: the model's, or
    ``[decision] threshold`` over it (chosen in one place, ``model.draem.predictor.load_predictor``), the same the
    model's early exit stops on. A test's fake detector may be given another."""

    def __init__(self, camera: Camera, inspector: Inspector | PairInspector, link: LineLink,
                 inspection_log: InspectionLog, *,
                 cycle_time_ms: float, threshold: float | None = None, queue_size: int = 4,
                 backpressure: str = "drop_oldest",
                 grab_timeout_ms: int = 1000, viewer: ViewerFeed | None = None,
                 rejects: RejectStore | None = None, settle_timeout_s: float = 2.0,
                 drift: DriftMonitor | None = None, second_drift: DriftMonitor | None = None,
                 max_frame_delay_ms: float | None = None) -> None:
        self.camera, self.inspector, self.link, self.log = camera, inspector, link, inspection_log
        self.threshold = inspector.detector.threshold if threshold is None else threshold
        second = inspector.second.detector if isinstance(inspector, PairInspector) else None
        self.second_threshold = second.threshold if second is not None else None
        """The second camera's threshold (``[second_camera]``); None with one camera."""
        self.second_model_id = second.model_id if second is not None else None
        self.frames_per_part = camera.config.frames_per_part
        """Frames that make one part (the camera's ``frames_per_part``, from ``[camera] dome_segments``): the station
        triggers each (software trigger)."""
        self.cycle_time_ms, self.grab_timeout_ms = cycle_time_ms, grab_timeout_ms
        inspector.slow_priors_ms = SLOW_PRIORS_SHARE * cycle_time_ms
        self.settle_timeout_s = settle_timeout_s
        self.max_frame_delay_ms = frame_delay_limit_ms(max_frame_delay_ms, cycle_time_ms)
        """Line trigger: a frame exposed later than this after a part's TRIG reached the host (``TransferClock``) is
        the next part's (the camera missed this part's pulse): this part is rejected and the frame kept for the next;
        one exposed earlier than this before it is an earlier part's (skipped). Default: the cycle time (such a frame
        could only make its part late)."""
        if max_frame_delay_ms is None and link.triggered and camera.config.trigger.startswith("line"):
            log.warning("line trigger without [acquisition] max_frame_delay_ms: a pulse the camera misses is caught "
                        "only when parts come more than the cycle time (%.0f ms) apart; set it below the part spacing "
                        "(docs/bring-up.md, step 8)", cycle_time_ms)
        self.watches = [CameraWatch(drift)] + ([CameraWatch(second_drift, SECOND_NAME, view=False)]
                                               if second is not None else [])
        """Per camera (the first, then the second when there is one, ``second_drift`` its drift monitor), a rolling
        window of its judged frames' statistics against its model's training range (``drift``: None, no check) and,
        the first camera's, how many of its last judged parts lay partly outside its model's view
        (``unseen_fraction``; ``station.drift.CameraWatch`` says why not the second's): their warnings are logged
        when they start and stop, kept in every row's ``drift`` while they last (the second camera's named for it),
        and shown in the viewer."""
        self.queue: FrameQueue[Part] = FrameQueue(queue_size, backpressure)
        self.viewer = viewer
        self.rejects = rejects
        self.stats = LiveStats()
        self._stop = threading.Event()
        self._dropped: deque[Part] = deque()
        self._last_frame: tuple[int, float] | None = None  # (frame id, perf_counter) of the newest frame
        self._line_last_id: int | None = None  # line trigger: the newest frame id taken from the camera
        self._held: Frame | None = None  # line trigger: a frame kept for the part it belongs to, after lost ones
        self._owed = 0  # line trigger: parts still to come whose frames were lost before the held one
        self._transfer = TransferClock()
        self._unusable = 0  # grabs in a row that raised something other than a timeout or a lost camera
        self._model: ModelThread | None = None  # the inspector on its own thread, while ``run`` runs
        self._model_busy = 0  # parts rejected as "model busy" since the model took its current frame
        self._grabbed = 0
        self._count_lock = threading.Lock()
        self._counter = 0
        self._records = RecordKeeper(inspection_log)
        self._written: tuple[Part, InspectionRecord, bool] | None = None  # the part being processed: its row, PLC
        self._answered: Part | None = None  # ... and whether the PLC was told (``_process_failed``)
        self.stale_frames = 0
        """Frames skipped because they were completed before their part could have been imaged."""
        self.collector_pauses: CollectorPauses | None = None
        """The garbage collector's pauses during ``run`` (``station.heap``), once it has started."""
        self.fatal: str | None = None

    # -- acquisition thread -------------------------------------------------------------------------------
    def _next_part(self) -> Part | None:
        if self.link.triggered:
            trigger = self.link.next_trigger(timeout_s=0.2)
            if trigger is None:
                return None
            part = Part(trigger.part_id, trigger.t_arrival)
            age_ms = 1e3 * (time.perf_counter() - trigger.t_arrival)
            if age_ms > self.cycle_time_ms and self.camera.config.trigger == "software":
                # no frame belongs to it yet, and any frame now would come too late: answer it at once
                part.late_ms = age_ms
                return part
        else:
            self._counter += 1
            part = Part(str(self._counter), time.perf_counter())
        if self._owed:
            self._owed -= 1
            part.error = f"no frame for part {part.part_id}: its frame was lost in transport (a gap in frame ids)"
            part.grab_ms = 1e3 * (time.perf_counter() - part.t_trigger)
            return part
        try:
            part.frame = self._grab_for(part)
            if self.frames_per_part > 1:
                part.frames = self._grab_set(part, part.frame)
        except FramesLost as exc:
            part.error = f"no frame for part {part.part_id}: {exc}"
        except SetIncomplete as exc:
            part.error = f"frame set incomplete for part {part.part_id}: {exc}"
        except CameraTimeout as exc:
            if not self.link.triggered:  # free run: no part was announced, nothing to judge
                log.warning("grab timeout without a trigger: %s", exc)
                return None
            part.error = f"no frame for part {part.part_id}: {exc}"
            if self._line_last_id is not None:  # line trigger: its frame id, if the camera made it, is spent
                self._line_last_id += 1
        except CameraError as exc:  # lost camera (after the driver's reconnects): judge this part, then stop
            part.error = f"camera error for part {part.part_id}: {exc}"
            self.fatal = str(exc)
            self._stop.set()
        except Exception as exc:  # a frame that cannot be read, a trigger call that failed: this part only
            self._unusable += 1
            why = f"{type(exc).__name__}: {exc}"
            if self._unusable >= MAX_UNUSABLE_FRAMES:  # a camera that gives nothing usable is a lost camera
                self.fatal = f"{self._unusable} grabs in a row gave no usable frame, the last: {why}"
                self._stop.set()
            if not self.link.triggered:
                log.warning("frame not usable without a trigger: %s", why)
                return None
            log.warning("no usable frame for part %s: %s", part.part_id, why)
            part.error = f"no usable frame for part {part.part_id}: {why}"
        else:
            self._unusable = 0
        part.grab_ms = 1e3 * (time.perf_counter() - part.t_trigger)
        return part

    def _grab_set(self, part: Part, first: Frame) -> tuple[Frame, ...]:
        """``first`` and the rest of ``part``'s frames (``frames_per_part``), each taken as ``_grab_for`` takes the
        first: software trigger, each triggered, never a frame completed before its own trigger; line trigger (the
        sequencer pulses the camera once per segment), never a frame exposed beyond ``max_frame_delay_ms`` after the
        part's TRIG: a missed pulse spends no frame id, and the frame after it is the next part's (FramesLost, the
        frame kept for that part). SetIncomplete when a frame does not come within the grab timeout (a frame
        arriving after that is taken before the next trigger, or too late for the next TRIG: skipped)."""
        frames = [first]
        for k in range(1, self.frames_per_part):
            try:
                frames.append(self._grab_for(part))
            except CameraTimeout as exc:
                if self._line_last_id is not None:  # as for a part's only frame: its id, if made, is spent
                    self._line_last_id += 1
                raise SetIncomplete(f"frame {k + 1} of {self.frames_per_part} did not come: {exc}") from None
        return tuple(frames)

    def _grab_for(self, part: Part) -> Frame:
        """The frame of ``part``: triggered, frames completed before the part could have been imaged are an earlier
        part's (one that arrived after its own part timed out) and are skipped, never judged for this part.
        Software trigger: before ``trigger()``; hardware trigger: over a cycle before the TRIG reached the host, line
        trigger with a PLC: over ``max_frame_delay_ms`` before it (a part's frames lie within that of its TRIG, either
        side: a frame a part gave up on as too late is not taken by the next part either, which would judge every
        later part on its predecessor's frames).
        "Completed" is on the host, less any transfer time above the quickest lately (``TransferClock``, from the
        camera's timestamps): a frame held up by a network stall past its grab's timeout, arriving after the next
        part's trigger, was still taken before it.
        Line trigger: frames are the parts' in order, so a gap in frame ids means the frames of this part and of
        the parts after it were lost in transport: FramesLost for this part, the owed parts are rejected without a
        grab, and the frame is held for its own part (``MAX_HELD_GAP``). A frame that would have completed more than
        ``max_frame_delay_ms`` after the part's TRIG, had its transfer been as quick as the quickest lately
        (``TransferClock``), is a later part's (the camera missed this part's pulse, which spends no frame id):
        FramesLost for this part, and the frame is held for the next. A frame late only in transfer stays its own
        part's. With more than one frame per part (``_grab_set``) every frame is checked so, triggered by the PLC or
        not: a set must not mix two parts' frames, nor one frame twice."""
        software = self.camera.config.trigger == "software"
        line = self.link.triggered and self.camera.config.trigger.startswith("line")
        if software:
            earliest = time.perf_counter()
            self.camera.trigger()
        else:  # hardware trigger; on a line trigger with a PLC the TRIG may reach the host after the pulse, by as
            # much as a frame may come after it
            earliest = part.t_trigger - (self.max_frame_delay_ms if line else self.cycle_time_ms) / 1e3
        deadline = time.perf_counter() + self.grab_timeout_ms / 1e3
        while True:
            remaining_ms = max(1, int(1e3 * (deadline - time.perf_counter())))
            if self._held is not None:  # already matched to this part by its frame id
                frame, self._held = self._held, None
            else:
                frame = self.camera.grab(remaining_ms)
                if line:
                    self._check_line_frame(frame)
            if (not self.link.triggered and self.frames_per_part == 1) or frame.host_timestamp_ns <= 0:
                return frame
            completed = perf_from_host_ns(frame.host_timestamp_ns)
            exposed = self._transfer.fastest(frame, completed)  # less a slow transfer: when it was taken
            delay_ms = 1e3 * (exposed - part.t_trigger) if line else 0.0
            if delay_ms > self.max_frame_delay_ms:
                self._held = frame
                raise FramesLost(f"the camera missed its trigger pulse: the next frame ({frame.frame_id}) was "
                                 f"exposed {delay_ms:.0f} ms after its TRIG, over [acquisition] max_frame_delay_ms "
                                 f"({self.max_frame_delay_ms:.0f} ms); the frame is kept for the next part")
            if exposed >= earliest - CLOCK_PAIR_S:  # within the clocks' pairing error: its own part's
                return frame
            self.stale_frames += 1
            log.warning("frame %d was taken %.0f ms before part %s could be imaged: an earlier part's, skipped",
                        frame.frame_id, 1e3 * (earliest - exposed), part.part_id)
            if time.perf_counter() >= deadline:
                raise CameraTimeout(f"no frame of its own within {self.grab_timeout_ms} ms (only earlier parts')")

    def _check_line_frame(self, frame: Frame) -> None:
        """Line trigger: raise FramesLost when frame ids are missing before ``frame`` (held for its own part when
        at most ``MAX_HELD_GAP`` are); a counter that restarts (a lower id, after a reconnect) starts a new run."""
        last, self._line_last_id = self._line_last_id, frame.frame_id
        if last is None or frame.frame_id <= last + 1:
            return
        missing = frame.frame_id - last - 1
        if missing <= MAX_HELD_GAP:
            self._held, self._owed = frame, missing - 1
            raise FramesLost(f"its frame was lost in transport ({missing} frame id(s) missing between {last} and "
                             f"{frame.frame_id}); frame {frame.frame_id} is kept for the part {missing} trigger(s) "
                             "later")
        raise FramesLost(f"frame ids jumped from {last} to {frame.frame_id}: which part frame {frame.frame_id} "
                         "belongs to cannot be told, so it is dropped")

    def _note_lost_frames(self, part: Part) -> None:
        """Free run: frames missing between two frame ids never reached the host, one not-inspected row each, at
        most as many as the camera could have made in the time between (a reset counter is no lost frames).
        Triggered: every announced part has its own row already; a gap adds none."""
        if part.frame is None:
            return
        now = time.perf_counter()
        fid = part.frame.frame_id  # the first of its set; the set's last is the newest
        if self._last_frame is not None and not self.link.triggered:
            last_id, last_t = self._last_frame
            possible = int((now - last_t) * self.camera.config.frame_rate_hz * 1.5) + 1
            for missing in range(last_id + 1, min(fid, last_id + 1 + possible, last_id + 1 + MAX_LOST_ROWS)):
                self._dropped.append(Part(f"frame-{missing}", part.t_trigger, announced=False,
                                          error=f"frame {missing} lost before reaching the host"))
        newest = part.taken[-1].frame_id
        if self._last_frame is None or newest > self._last_frame[0]:
            self._last_frame = (newest, now)

    def _acquire(self, max_parts: int | None) -> None:
        try:
            while not self._stop.is_set() and (max_parts is None or self._grabbed < max_parts):
                part = self._next_part()
                if part is None:
                    continue
                self._count_part()
                self._note_lost_frames(part)
                self._dropped.extend(self.queue.put(part))  # finished by the processing thread, which owns the log
        except Exception as exc:  # an acquisition bug must not leave processing waiting forever
            log.exception("acquisition stopped")
            self.fatal = f"acquisition failed: {exc}"
        finally:
            self.queue.close()

    def _count_part(self) -> None:
        with self._count_lock:
            self._grabbed += 1

    # -- processing ----------------------------------------------------------------------------------------
    def _finish_dropped(self) -> None:
        while self._dropped:
            part = self._dropped.popleft()
            reason = part.error or f"dropped: processing queue full ({self.queue.policy})"
            self._safely(part, lambda p=part, r=reason: self._finish(p, None, Decision(Verdict.REJECT, r),
                                                                     not_inspected=True))

    def _answer_expired(self) -> None:
        """Parts announced more than a cycle ago that acquisition has not taken (camera stalled or reconnecting,
        acquisition behind): rejected as late now, not when the camera comes back."""
        for trigger in self.link.expired(time.perf_counter() - self.cycle_time_ms / 1e3):
            self._count_part()
            age_ms = 1e3 * (time.perf_counter() - trigger.t_arrival)
            part = Part(trigger.part_id, trigger.t_arrival)
            self._safely(part, lambda p=part, a=age_ms: self._finish(
                p, None, late(a, self.cycle_time_ms, "no frame taken: camera or acquisition busy")))

    def _process(self, part: Part) -> None:
        inspection = None
        late_ms = part.late_ms if part.late_ms is not None else 1e3 * (time.perf_counter() - part.t_trigger)
        if part.error is None and part.frame is not None and late_ms <= self.cycle_time_ms:
            assert self._model is not None
            answer = self._model.inspect(part.part_id, part.taken, part.t_trigger + self.cycle_time_ms / 1e3)
            if isinstance(answer, NoAnswer):
                self._no_answer(part, answer)
                return
            self._model_busy = 0
            inspection = answer
            t = time.perf_counter()
            decision = decide(inspection.score, self.threshold, elapsed_ms=1e3 * (t - part.t_trigger),
                              cycle_time_ms=self.cycle_time_ms, error=inspection.error,
                              invalid_fraction=inspection.invalid_fraction, empty=inspection.empty_reason,
                              found=beyond_limits(inspection.checks))
            if inspection.second is not None:
                decision = join(decision, self._second_decision(inspection.second), SECOND_NAME)
            if decision.decision == Verdict.EMPTY and self.link.triggered:  # an announced part not seen: rejected,
                decision = Decision(Verdict.REJECT, decision.reason)  # at the PLC and in its row
            inspection.timings_ms["decision"] = 1e3 * (time.perf_counter() - t)
            for watch, seen in zip(self.watches, (inspection, inspection.second), strict=False):
                if seen is not None and seen.present:
                    for change in watch.update(seen.frame_stats, seen.checks):
                        log.warning("%s", change)
        elif part.error is None and (part.frame is not None or part.late_ms is not None):
            decision = late(late_ms, self.cycle_time_ms, "before the model could start")
        else:
            decision = decide(None, self.threshold, error=part.error or "no frame")
        self._finish(part, inspection, decision)

    def _second_decision(self, second: Inspection) -> Decision:
        """The second camera's own decision on its threshold (its time is the part's, judged on the first's)."""
        assert self.second_threshold is not None
        return decide(second.score, self.second_threshold, error=second.error,
                      invalid_fraction=second.invalid_fraction, empty=second.empty_reason,
                      found=beyond_limits(second.checks))

    def _no_answer(self, part: Part, answer: NoAnswer) -> None:
        """The model did not answer by the part's deadline, or is still on an earlier part: reject it now;
        ``MAX_MODEL_BUSY_PARTS`` busy in a row stop the station."""
        self._model_busy = self._model_busy + 1 if answer.busy else 0
        if self._model_busy >= MAX_MODEL_BUSY_PARTS:
            self.fatal = f"the model gave no answer while {self._model_busy} parts came: {answer.reason}"
            log.error("%s: stopping", self.fatal)
            self._stop.set()
        decision = (decide(None, self.threshold, error=answer.reason) if answer.busy else
                    late(1e3 * (time.perf_counter() - part.t_trigger), self.cycle_time_ms, answer.reason))
        self._finish(part, None, decision)

    def _safely(self, part: Part, step: Callable[[], None]) -> None:
        """``step`` (judging or answering ``part``); an error it does not handle itself (a bug, a failing reject
        store) rejects the part with the error, in its row and at the PLC (``_process_failed``), and stops the
        station as a lost camera does."""
        self._written, self._answered = None, None
        try:
            step()
        except Exception as exc:
            self._process_failed(part, exc)

    def _process_failed(self, part: Part, exc: Exception) -> None:
        """The part gets its one row and its REJECT, whichever step failed: no row yet, a row and the reject; a row not
        yet told to the PLC, the row amended (a pass) and the reject. Then the station stops; the parts already
        taken are judged, and later triggers refused, as at any stop."""
        why = f"station error: {type(exc).__name__}: {exc}"
        log.exception("part %s: %s; it is rejected and the station stops", part.part_id, why)
        self.fatal = self.fatal or f"processing part {part.part_id} failed: {why}"
        self._stop.set()
        decision = Decision(Verdict.REJECT, f"not judged: {why}")
        try:
            if self._written is None or self._written[0] is not part:
                self._finish(part, None, decision, plain=True)
            elif self._answered is not part and self._written[2]:
                record = self._written[1]
                if record.decision == Verdict.PASS:
                    record = self._records.amend(record, decision)
                self.link.report(part.part_id, Verdict.REJECT, record.reason,
                                 deadline=part.t_trigger + self.cycle_time_ms / 1e3)
        except Exception:
            log.exception("part %s could not be answered after that error", part.part_id)

    def _finish(self, part: Part, inspection: Inspection | None, decision: Decision,
                not_inspected: bool = False, plain: bool = False) -> None:
        """Record the part (write-ahead: durable before the PLC hears of it), then tell the PLC, update statistics
        and the viewer. A row that cannot be written turns the decision into a reject (fail closed). ``plain``:
        without the reject's image and the viewer (answering after an error, ``_process_failed``)."""
        t_decided = time.perf_counter()
        empty = decision.decision == Verdict.EMPTY
        # an announced part that is not in view fails closed (REJECT); trigger-free, an empty frame is no part
        tell_plc = part.announced and self.link.has_plc and (self.link.triggered or not empty)
        frame = part.frame
        gt = part_truth(frame)
        # no part in view has no good/defective label: logged as unknown, counted as "none" in the statistics
        truth = gt.label if gt is not None and gt.present else None
        timings = inspection.timings_ms if inspection else {}
        priors_ms = timings.get("priors")
        if priors_ms is not None and "presence" in timings:
            priors_ms += timings["presence"]  # the log has no column of its own for the check (~0.1 ms)
        second = inspection.second if inspection is not None else None  # the second camera's, with one
        companion = frame.companion if frame is not None else None
        image_path = None
        if (not plain and self.rejects is not None and frame is not None and decision.decision != Verdict.PASS
                and (not empty or tell_plc)):
            image_path = self.rejects.save(part.part_id, frame.frame_id, frame.raw,
                                           inspection.heatmap if inspection else None,
                                           later=tuple(f.raw for f in part.frames[1:]),
                                           second_raw=companion.raw if companion is not None else None,
                                           second_heatmap=second.heatmap if second is not None else None)
        record = InspectionRecord(
            decision=Verdict.NOT_INSPECTED if not_inspected else decision.decision, time_unix_s=time.time(),
            part_id=part.part_id, camera_frame_id=frame.frame_id if frame else None,
            camera_timestamp_ns=frame.timestamp_ns if frame else None,
            score=inspection.score if inspection else None, threshold=self.threshold,
            model_id=self.inspector.detector.model_id, reason=decision.reason, grab_ms=part.grab_ms,
            demosaic_ms=timings.get("demosaic"), priors_ms=priors_ms, model_ms=timings.get("model"),
            decision_ms=timings.get("decision"), io_ms=None, total_ms=1e3 * (t_decided - part.t_trigger),
            io_delivered=False if tell_plc else None, ground_truth_label=truth,
            ground_truth_present=gt.present if gt is not None else None, image_path=image_path,
            **({k: getattr(inspection.frame_stats, k) for k in LOGGED_STATISTICS}
               if inspection is not None and inspection.frame_stats else {}),
            drift="; ".join(w for w in (watch.warning for watch in self.watches) if w) or None,
            **{k: inspection.checks[k] for k in FRAME_CHECKS if inspection is not None and k in inspection.checks},
            second_score=second.score if second is not None else None, second_threshold=self.second_threshold,
            second_model_id=self.second_model_id, second_frame_id=companion.frame_id if companion is not None else None)
        record = self._records.write(record, awaits_plc=tell_plc, t_decided=t_decided)
        self._written = (part, record, tell_plc)
        if tell_plc and record.decision == Verdict.PASS:
            late_ms = 1e3 * (time.perf_counter() - part.t_trigger)
            if late_ms > self.cycle_time_ms:  # writing the row took the rest of the cycle: a late PASS is no PASS
                record = self._records.amend(record, late(late_ms, self.cycle_time_ms, "with its log row"))
                self._written = (part, record, tell_plc)
        if tell_plc:
            self.link.report(part.part_id, Verdict.PASS if record.decision == Verdict.PASS else Verdict.REJECT,
                             record.reason,
                             deadline=part.t_trigger + self.cycle_time_ms / 1e3)
        self._answered = part
        self.stats.add(record.decision, record.total_ms, gt.label if gt is not None else None,
                       gt.present if gt is not None else True)
        if not plain and self.viewer is not None and inspection is not None and "intensity" in inspection.priors:
            self._show(part, inspection, record)

    def _show(self, part: Part, inspection: Inspection, record: InspectionRecord) -> None:
        """The part in the viewer. The viewer is a display: an error in it is logged once, and the station goes on
        without it (it used to end processing, leaving the parts behind without answer or row)."""
        assert self.viewer is not None
        p = inspection.priors
        try:
            self.viewer.put(ViewFrame(part.part_id, record.decision, inspection.score, self.threshold,
                                      p["intensity"], p.get("dolp"), p.get("aolp"), p.get("normal"),
                                      inspection.heatmap, "\n".join(t for t in (record.reason, record.drift) if t),
                                      self.stats.summary(),
                                      {k: v for k in FRAME_CHECKS if (v := getattr(record, k)) is not None},
                                      tilt=p.get("tilt_x")))
        except Exception:
            log.exception("the viewer failed on part %s; inspection goes on without it", part.part_id)
            self.viewer = None

    def _refused(self, trigger: Trigger) -> str:
        """A part announced while the station stops: recorded, then rejected (``LineLink.refuse_triggers``)."""
        reason = f"not judged: station stopping ({self.fatal})" if self.fatal else "not judged: station stopping"
        record = InspectionRecord(Verdict.REJECT, time.time(), part_id=trigger.part_id, threshold=self.threshold,
                                  model_id=self.inspector.detector.model_id, reason=reason,
                                  total_ms=1e3 * (time.perf_counter() - trigger.t_arrival), io_delivered=False)
        record = self._records.write(record, awaits_plc=True, t_decided=time.perf_counter())
        self.stats.add(record.decision, record.total_ms, None)
        return reason

    # -- control -------------------------------------------------------------------------------------------
    @property
    def grabbed(self) -> int:
        """Parts taken so far: by acquisition, or answered as late while it was busy (each ends in one log row;
        frames lost in transport add theirs). ``run(max_parts)`` stops at this count."""
        return self._grabbed

    @property
    def unrecorded(self) -> int:
        """Rows that could not be written yet (disk full or failing), kept in memory and retried every cycle."""
        return self._records.backlog

    @property
    def unrecorded_rows(self) -> int:
        """Rows never written, or left saying pass for a part answered REJECT (the disk stayed full; each went to the
        process log at shutdown: ``UNRECORDED ROW`` as JSON, ``UNRECORDED AMENDMENT``)."""
        return self._records.lost_rows

    def run(self, max_parts: int | None = None, progress_every_s: float = 5.0) -> LiveStats:
        """Inspect until ``max_parts`` parts arrived, ``stop()``, or a fatal camera error; answer every part
        announced until the link is closed; return the statistics. What is alive when it starts (the model, the
        libraries) is frozen out of the garbage collector's sight until it ends (``station.heap``; ``station run``
        collects before it opens any device)."""
        with frozen_heap(long_ms=COLLECTOR_PAUSE_SHARE * self.cycle_time_ms) as pauses:
            self.collector_pauses = pauses
            self._run(max_parts, progress_every_s)
        if pauses.long:
            log.warning("the garbage collector held the station %d time(s) for %.0f ms or more (longest %.0f ms)",
                        pauses.long, pauses.long_ms, pauses.longest_ms)
        return self.stats

    def _run(self, max_parts: int | None, progress_every_s: float) -> None:
        """``run``'s threads and loop."""
        acq = threading.Thread(target=self._acquire, args=(max_parts,), name="acquisition", daemon=True)
        self._model = ModelThread(self.inspector.inspect)
        self.camera.start()
        acq.start()
        last = time.perf_counter()
        poll_s = min(0.2, self.cycle_time_ms / 2e3)
        try:
            while True:
                try:
                    part = self.queue.get(timeout_s=poll_s)
                except Closed:
                    break
                self._finish_dropped()
                if part is not None:
                    self._safely(part, lambda p=part: self._process(p))
                self._answer_expired()
                self._records.settle(self.link.outcomes())
                if time.perf_counter() - last > progress_every_s:
                    last = time.perf_counter()
                    log.info("%s", ", ".join(f"{k} {v:.4g}" for k, v in self.stats.summary().items()))
        finally:
            self._stop.set()
            acq.join(timeout=5)
            self.camera.stop()
            self._finish_dropped()
            self._shut_down_link()
            self._model.close()
            self.inspector.close()

    def _shut_down_link(self) -> None:
        """Every part announced from now on is recorded and rejected until the port closes; wait (up to
        ``settle_timeout_s``) for the PLC's acknowledgements; record them; close the link."""
        self.link.refuse_triggers(self._refused)
        self.link.flush(self.settle_timeout_s)
        self.link.close()
        self._records.settle(self.link.outcomes())
        self._records.give_up()

    def stop(self) -> None:
        self._stop.set()

    def run_until_signal(self, max_parts: int | None = None) -> LiveStats:
        """``run`` with SIGINT/SIGTERM mapped to a clean ``stop`` (main thread only)."""
        with self.stop_on_signals():
            return self.run(max_parts)

    @contextlib.contextmanager
    def stop_on_signals(self) -> Iterator[None]:
        """SIGINT/SIGTERM call ``stop`` while inside (main thread only): the queue drains and every trigger until
        the port closes is answered and logged. ``station run --viewer`` runs the station in a thread beside the
        Qt loop under it (the viewer's timer lets Python run the handler)."""
        previous = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
        for s in previous:
            signal.signal(s, lambda *_: self.stop())
        try:
            yield
        finally:
            for s, handler in previous.items():
                signal.signal(s, handler)
