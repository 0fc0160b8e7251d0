"""The inspection loop: one log row per part, fail closed, backpressure logged, PLC told about every part."""

from __future__ import annotations

import time

import numpy as np
import pytest

from drivers.camera import CameraBase, CameraConfig
from drivers.errors import CameraLost, CameraTimeout
from drivers.frame import Frame, GroundTruth
from model.priors import IMX250MZR
from station.inspection_log import InspectionLog
from station.inspector import Inference, Inspector
from station.loop import NoLink, Station


class ScriptedCamera(CameraBase):
    """Frames whose mean brightness encodes the part's label; ``script`` entries may be exceptions to raise."""

    def __init__(self, script, trigger="free_run"):
        super().__init__(CameraConfig(trigger=trigger))
        self.script = list(script)
        self.triggers = 0
        self.frame_id = 0

    def open(self): ...
    def close(self): ...
    def start(self): ...
    def stop(self): ...
    def configure(self, config): ...

    def trigger(self):
        self.triggers += 1

    def grab(self, timeout_ms=None):
        if not self.script:
            raise CameraTimeout("script exhausted")
        item = self.script.pop(0)
        if isinstance(item, Exception):
            raise item
        self._stats.completed += 1
        self.frame_id += 1 + (item == "gap") * 3  # "gap": three frames lost in transport before this one
        raw = np.full((8, 8), 200 if item == 1 else 20, np.uint8)
        return Frame(raw, "Mono8", 8, self.frame_id, 0, time.time_ns(),
                     ground_truth=GroundTruth(label=int(item == 1)))


class BrightnessDetector:
    """Score = mean intensity: bright (defective) parts score high. ``fail_on`` raises, ``delay_s`` is slow."""

    model_id = "test-brightness"
    threshold = 0.5
    priors = ("intensity",)

    def __init__(self, delay_s=0.0, nan=False, fail=False):
        self.delay_s, self.nan, self.fail = delay_s, nan, fail

    def infer(self, priors):
        time.sleep(self.delay_s)
        if self.fail:
            raise RuntimeError("weights corrupt")
        return Inference(float("nan") if self.nan else float(priors["intensity"].mean()) * 2)


class ScriptedLink:
    triggered = True

    def __init__(self, n):
        self.pending = [f"T{i}" for i in range(n)]
        self.reports = []

    def next_trigger(self, timeout_s):
        return self.pending.pop(0) if self.pending else None

    def report(self, part_id, decision, reason):
        self.reports.append((part_id, decision))
        return True


def make_station(tmp_path, camera, detector, link=None, **kw):
    log = InspectionLog(tmp_path / "log.sqlite")
    kw.setdefault("cycle_time_ms", 10_000.0)
    return Station(camera, Inspector(detector, IMX250MZR), link or NoLink(), log,
                   threshold=detector.threshold, **kw), log


def test_every_part_is_judged_logged_and_scored_against_truth(tmp_path):
    labels = [0, 1, 0, 0, 1, 1, 0, 0]
    station, log = make_station(tmp_path, ScriptedCamera(labels), BrightnessDetector(), queue_size=16,
                                backpressure="block")
    stats = station.run(max_parts=len(labels))
    rows = list(log.rows())
    assert [r["decision"] for r in rows] == ["reject" if x else "pass" for x in labels]
    assert stats.confusion == {"good_pass": 5, "bad_reject": 3}
    assert all(r["total_ms"] >= r["demosaic_ms"] + r["priors_ms"] for r in rows)
    assert rows[1]["reason"].startswith("score 1.5686 > threshold 0.5000")


def test_backpressure_drops_are_logged_as_not_inspected_and_rejected_at_the_plc(tmp_path):
    n = 40
    link = ScriptedLink(n)
    station, log = make_station(tmp_path, ScriptedCamera([0] * n, trigger="software"),
                                BrightnessDetector(delay_s=0.01), link, queue_size=2, backpressure="drop_oldest")
    station.run(max_parts=n)
    rows = list(log.rows())
    assert len(rows) == n  # row count = parts grabbed, dropped ones included
    dropped = [r for r in rows if r["decision"] == "not_inspected"]
    assert dropped and all("queue full (drop_oldest)" in r["reason"] for r in dropped)
    plc = dict(link.reports)
    assert len(plc) == n and all(plc[r["part_id"]] == "reject" for r in dropped)
    assert station.camera.triggers == n


@pytest.mark.parametrize(("detector", "reason"), [
    (BrightnessDetector(nan=True), "model score is nan"),
    (BrightnessDetector(fail=True), "model test-brightness failed: RuntimeError: weights corrupt"),
])
def test_unjudgeable_parts_are_rejected_and_the_loop_keeps_going(tmp_path, detector, reason):
    station, log = make_station(tmp_path, ScriptedCamera([0, 0, 0]), detector, queue_size=8, backpressure="block")
    station.run(max_parts=3)
    rows = list(log.rows())
    assert len(rows) == 3 and all(r["decision"] == "reject" and reason in r["reason"] for r in rows)


def test_over_cycle_time_is_rejected(tmp_path):
    station, log = make_station(tmp_path, ScriptedCamera([0, 0]), BrightnessDetector(delay_s=0.05),
                                queue_size=8, backpressure="block", cycle_time_ms=20.0)
    station.run(max_parts=2)
    assert all("not judged in time" in r["reason"] for r in log.rows())


def test_triggered_part_without_a_frame_is_rejected(tmp_path):
    link = ScriptedLink(3)
    camera = ScriptedCamera([0, CameraTimeout("no frame in 1000 ms"), 0], trigger="software")
    station, log = make_station(tmp_path, camera, BrightnessDetector(), link, queue_size=8, backpressure="block")
    station.run(max_parts=3)
    rows = {r["part_id"]: r for r in log.rows()}
    assert rows["T1"]["decision"] == "reject" and "no frame for part T1" in rows["T1"]["reason"]
    assert dict(link.reports) == {"T0": "pass", "T1": "reject", "T2": "pass"}


def test_lost_camera_rejects_the_part_and_stops(tmp_path):
    camera = ScriptedCamera([0, 0, CameraLost("192.0.2.7 stopped answering"), 0, 0])
    station, log = make_station(tmp_path, camera, BrightnessDetector(), queue_size=8, backpressure="block")
    station.run(max_parts=None)
    rows = list(log.rows())
    assert [r["decision"] for r in rows] == ["pass", "pass", "reject"]
    assert "192.0.2.7 stopped answering" in rows[-1]["reason"] and station.fatal


def test_frames_lost_in_transport_are_logged_not_inspected_but_not_sent_to_the_plc(tmp_path):
    link = ScriptedLink(3)
    camera = ScriptedCamera([0, "gap", 0], trigger="software")
    station, log = make_station(tmp_path, camera, BrightnessDetector(), link, queue_size=8, backpressure="block")
    station.run(max_parts=3)
    rows = list(log.rows())
    lost = [r for r in rows if r["decision"] == "not_inspected"]
    assert [r["part_id"] for r in lost] == ["frame-2", "frame-3", "frame-4"]
    assert all("lost before reaching the host" in r["reason"] and r["io_delivered"] is None for r in lost)
    assert len(rows) == 6 and dict(link.reports) == {"T0": "pass", "T1": "pass", "T2": "pass"}
