"""The inspection loop: trigger -> grab -> demosaic -> priors -> model -> decision -> PLC -> log.

Acquisition runs in its own thread and hands parts to processing through a bounded ``FrameQueue`` with the
configured backpressure. Every part ends in exactly one log row:

- judged: ``pass`` or ``reject`` (with the reason);
- could not be judged (grab timeout after a trigger, lost camera, priors or model error, NaN score, over the
  cycle time): ``reject`` with the reason, and the PLC is told REJECT (fail closed);
- dropped by backpressure: ``not_inspected`` with the reason, and the PLC is told REJECT;
- no part in view (``station.presence``, before the model runs): ``empty`` with the check's value as reason.
  When the PLC announced a part (triggered), the PLC is told REJECT: a part was expected and not seen (missing,
  misplaced, or a part the check cannot see), and an unseen part must never pass. Trigger-free, an empty frame
  is the gap between parts: the PLC is told nothing and no image is kept.

``stop()`` (or SIGINT/SIGTERM through ``run_until_signal``) ends acquisition, drains the queue and flushes the log.
"""

from __future__ import annotations

import logging
import signal
import threading
import time
from collections import Counter, deque
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from drivers.camera import Camera
from drivers.errors import CameraError, CameraTimeout
from drivers.frame import Frame
from station.decision import Decision, decide
from station.frame_queue import Closed, FrameQueue
from station.inspection_log import InspectionLog, InspectionRecord
from station.inspector import Inspection, Inspector
from station.reject_store import RejectStore
from station.viewer import ViewerFeed, ViewFrame

log = logging.getLogger(__name__)

MAX_LOST_ROWS = 10000
"""At most this many rows for one gap in frame ids (a camera reset can jump its counter by millions)."""


class LineLink(Protocol):
    """The station's side of the PLC link (``drivers.line_io`` and the simulated PLC provide it)."""

    triggered: bool
    """True: one part per PLC trigger; False: trigger-free, every frame is a part."""

    def next_trigger(self, timeout_s: float) -> str | None:
        """The next part id, or None when no part arrived within ``timeout_s``."""
        ...

    def report(self, part_id: str, decision: str, reason: str | None) -> bool | None:
        """Send PASS/REJECT for ``part_id``; True delivered, False queued for later delivery, None no PLC."""
        ...


class NoLink:
    """Trigger-free operation without a PLC: every frame is a part, decisions go only to the log."""

    triggered = False

    def next_trigger(self, timeout_s: float) -> str | None:
        return None

    def report(self, part_id: str, decision: str, reason: str | None) -> bool | None:
        return None


@dataclass
class Part:
    """A part between acquisition and processing."""

    part_id: str
    t_trigger: float
    """``time.perf_counter()`` when the part arrived (trigger, or grab start when trigger-free)."""
    frame: Frame | None = None
    grab_ms: float | None = None
    error: str | None = None
    announced: bool = True
    """False for frames lost in transport: no PLC part id to answer."""


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

    def add(self, decision: str, total_ms: float | None, truth: int | None, present: bool = True) -> None:
        """One part; ``truth``: its label where known (None: no ground truth), ``present``: whether the ground
        truth has a part in view."""
        self.counts[decision] += 1
        if total_ms is not None:
            self.latencies_ms.append(total_ms)
        if truth is not None and decision in ("pass", "reject", "empty"):
            kind = "none" if not present else "bad" if truth else "good"
            self.confusion[f"{kind}_{decision}"] += 1

    def summary(self) -> dict[str, float]:
        n = sum(self.counts.values())
        lat = np.array(self.latencies_ms) if self.latencies_ms else np.zeros(1)
        return {"parts": n, "rejects": self.counts["reject"], "empty": self.counts["empty"],
                "not_inspected": self.counts["not_inspected"],
                "parts_per_s": n / max(time.perf_counter() - self.started, 1e-9),
                "p50_ms": float(np.percentile(lat, 50)), "p99_ms": float(np.percentile(lat, 99))}


class Station:
    """Runs the loop over one camera, inspector, PLC link and log (all opened by the caller)."""

    def __init__(self, camera: Camera, inspector: Inspector, link: LineLink, inspection_log: InspectionLog, *,
                 threshold: float, cycle_time_ms: float, queue_size: int = 4, backpressure: str = "drop_oldest",
                 grab_timeout_ms: int = 1000, viewer: ViewerFeed | None = None,
                 rejects: RejectStore | None = None) -> None:
        self.camera, self.inspector, self.link, self.log = camera, inspector, link, inspection_log
        self.threshold, self.cycle_time_ms, self.grab_timeout_ms = threshold, cycle_time_ms, grab_timeout_ms
        self.queue: FrameQueue[Part] = FrameQueue(queue_size, backpressure)
        self.viewer = viewer
        self.rejects = rejects
        self.stats = LiveStats()
        self._stop = threading.Event()
        self._dropped: deque[Part] = deque()
        self._last_frame_id: int | None = None
        self._grabbed = 0
        self._counter = 0
        self.fatal: str | None = None

    # -- acquisition thread -------------------------------------------------------------------------------
    def _next_part(self) -> Part | None:
        if self.link.triggered:
            part_id = self.link.next_trigger(timeout_s=0.2)
            if part_id is None:
                return None
        else:
            self._counter += 1
            part_id = str(self._counter)
        part = Part(part_id, time.perf_counter())
        try:
            if self.camera.config.trigger == "software":
                self.camera.trigger()
            part.frame = self.camera.grab(self.grab_timeout_ms)
        except CameraTimeout as exc:
            if not self.link.triggered:  # free run: no part was announced, nothing to judge
                log.warning("grab timeout without a trigger: %s", exc)
                return None
            part.error = f"no frame for part {part_id}: {exc}"
        except CameraError as exc:  # lost camera (after the driver's reconnects): judge this part, then stop
            part.error = f"camera error for part {part_id}: {exc}"
            self.fatal = str(exc)
            self._stop.set()
        part.grab_ms = 1e3 * (time.perf_counter() - part.t_trigger)
        return part

    def _note_lost_frames(self, part: Part) -> None:
        """Frames missing between two frame ids never reached the host: one not-inspected row each."""
        if part.frame is None:
            return
        fid = part.frame.frame_id
        if self._last_frame_id is not None:
            for missing in range(self._last_frame_id + 1, min(fid, self._last_frame_id + 1 + MAX_LOST_ROWS)):
                self._dropped.append(Part(f"frame-{missing}", part.t_trigger, announced=False,
                                          error=f"frame {missing} lost before reaching the host"))
        self._last_frame_id = fid

    def _acquire(self, max_parts: int | None) -> None:
        try:
            while not self._stop.is_set() and (max_parts is None or self._grabbed < max_parts):
                part = self._next_part()
                if part is None:
                    continue
                self._grabbed += 1
                self._note_lost_frames(part)
                self._dropped.extend(self.queue.put(part))  # finished by the processing thread, which owns the log
        except Exception as exc:  # an acquisition bug must not leave processing waiting forever
            log.exception("acquisition stopped")
            self.fatal = f"acquisition failed: {exc}"
        finally:
            self.queue.close()

    # -- processing ----------------------------------------------------------------------------------------
    def _finish_dropped(self) -> None:
        while self._dropped:
            part = self._dropped.popleft()
            reason = part.error or f"dropped: processing queue full ({self.queue.policy})"
            self._finish(part, None, Decision("reject", reason), not_inspected=True)

    def _process(self, part: Part) -> None:
        inspection = None
        if part.error is None and part.frame is not None:
            inspection = self.inspector.inspect(part.frame)
            t = time.perf_counter()
            empty = inspection.presence.reason if inspection.presence and not inspection.present else None
            decision = decide(inspection.score, self.threshold, elapsed_ms=1e3 * (t - part.t_trigger),
                              cycle_time_ms=self.cycle_time_ms, error=inspection.error,
                              invalid_fraction=inspection.invalid_fraction, empty=empty)
            inspection.timings_ms["decision"] = 1e3 * (time.perf_counter() - t)
        else:
            decision = decide(None, self.threshold, error=part.error or "no frame")
        self._finish(part, inspection, decision)

    def _finish(self, part: Part, inspection: Inspection | None, decision: Decision,
                not_inspected: bool = False) -> None:
        """Tell the PLC, log the part, update statistics and the viewer (processing thread only)."""
        t_decided = time.perf_counter()
        empty = decision.decision == "empty"
        # an announced part that is not in view fails closed (REJECT); trigger-free, an empty frame is no part
        tell_plc = part.announced and (self.link.triggered or not empty)
        to_plc = "reject" if empty else decision.decision
        delivered = self.link.report(part.part_id, to_plc, decision.reason) if tell_plc else None
        t_io = time.perf_counter()
        frame = part.frame
        gt = frame.ground_truth if frame is not None else None
        # no part in view has no good/defective label: logged as unknown, counted as "none" in the statistics
        truth = gt.label if gt is not None and gt.present else None
        timings = inspection.timings_ms if inspection else {}
        priors_ms = timings.get("priors")
        if priors_ms is not None and "presence" in timings:
            priors_ms += timings["presence"]  # the log has no column of its own for the check (~0.1 ms)
        image_path = None
        if (self.rejects is not None and frame is not None and decision.decision != "pass"
                and (not empty or tell_plc)):
            image_path = self.rejects.save(part.part_id, frame.frame_id, frame.raw,
                                           inspection.heatmap if inspection else None)
        record = InspectionRecord(
            decision="not_inspected" if not_inspected else decision.decision, time_unix_s=time.time(),
            part_id=part.part_id, camera_frame_id=frame.frame_id if frame else None,
            camera_timestamp_ns=frame.timestamp_ns if frame else None,
            score=inspection.score if inspection else None, threshold=self.threshold,
            model_id=self.inspector.detector.model_id, reason=decision.reason, grab_ms=part.grab_ms,
            demosaic_ms=timings.get("demosaic"), priors_ms=priors_ms, model_ms=timings.get("model"),
            decision_ms=timings.get("decision"), io_ms=1e3 * (t_io - t_decided),
            total_ms=1e3 * (t_decided - part.t_trigger),
            io_delivered=delivered, ground_truth_label=truth,
            ground_truth_present=gt.present if gt is not None else None, image_path=image_path)
        self.log.append(record)
        self.stats.add(record.decision, record.total_ms, gt.label if gt is not None else None,
                       gt.present if gt is not None else True)
        if self.viewer is not None and inspection is not None and "intensity" in inspection.priors:
            p = inspection.priors
            self.viewer.put(ViewFrame(part.part_id, decision.decision, inspection.score, self.threshold,
                                      p["intensity"], p.get("dolp"), p.get("aolp"), p.get("normal"),
                                      inspection.heatmap, decision.reason, self.stats.summary()))

    # -- control -------------------------------------------------------------------------------------------
    @property
    def grabbed(self) -> int:
        """Parts taken from the camera so far (each ends in one log row; frames lost in transport add theirs)."""
        return self._grabbed

    def run(self, max_parts: int | None = None, progress_every_s: float = 5.0) -> LiveStats:
        """Inspect until ``max_parts`` parts arrived, ``stop()``, or a fatal camera error; drain and return."""
        acq = threading.Thread(target=self._acquire, args=(max_parts,), name="acquisition", daemon=True)
        self.camera.start()
        acq.start()
        last = time.perf_counter()
        try:
            while True:
                try:
                    part = self.queue.get(timeout_s=0.2)
                except Closed:
                    break
                self._finish_dropped()
                if part is not None:
                    self._process(part)
                if time.perf_counter() - last > progress_every_s:
                    last = time.perf_counter()
                    log.info("%s", ", ".join(f"{k} {v:.4g}" for k, v in self.stats.summary().items()))
        finally:
            self._stop.set()
            acq.join(timeout=5)
            self.camera.stop()
            self._finish_dropped()
        return self.stats

    def stop(self) -> None:
        self._stop.set()

    def run_until_signal(self, max_parts: int | None = None) -> LiveStats:
        """``run`` with SIGINT/SIGTERM mapped to a clean ``stop`` (main thread only)."""
        previous = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
        for s in previous:
            signal.signal(s, lambda *_: self.stop())
        try:
            return self.run(max_parts)
        finally:
            for s, handler in previous.items():
                signal.signal(s, handler)
