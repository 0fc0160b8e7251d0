"""``station view``: a viewer attached to a running station through its SQLite log (another connection)."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest

from model.priors.mosaic import stokes_to_mosaic
from model.priors.testing import detailed_stokes
from station.cli import main
from station.inspection_log import InspectionLog, InspectionRecord
from station.log_follower import LogFollower
from station.reject_store import RejectStore
from station.viewer import ViewerFeed


def record(decision: str, part: str, **kw: object) -> InspectionRecord:
    return InspectionRecord(decision=decision, time_unix_s=time.time(), part_id=part, total_ms=50.0, **kw)


def test_follower_shows_only_new_parts_with_the_saved_images_of_rejects(tmp_path: Path) -> None:
    station_log = InspectionLog(tmp_path / "log.sqlite")  # the station's own writer stays open throughout
    station_log.append(record("pass", "old"))
    feed = ViewerFeed(maxsize=8)
    follower = LogFollower(tmp_path / "log.sqlite", feed)
    assert follower.poll() == 0  # attached: history is not replayed
    s0, s1, s2 = detailed_stokes(48, 64)
    raw = (np.clip(stokes_to_mosaic(s0, s1, s2), 0, 1) * 255).astype(np.uint8)
    heat = np.zeros((48, 64), np.float32)
    heat[10:20, 10:20] = 0.9
    image = RejectStore(tmp_path / "rejects").save("P2", 2, raw, heat)
    station_log.append([record("pass", "P1", score=0.1, threshold=0.5),
                        record("reject", "P2", score=0.9, threshold=0.5, reason="score", image_path=image,
                               noise_level=1.2, highlight_fraction=0.05),
                        record("reject", "P3", score=0.8, threshold=0.5, image_path=str(tmp_path / "gone.npz"))])
    assert follower.poll() == 3 and follower.poll() == 0
    gone = feed.latest()  # the GUI shows the newest
    assert gone.part_id == "P3" and "unreadable" in gone.reason  # retention deleted it: said, not a crash
    follower2 = LogFollower(tmp_path / "log.sqlite", feed := ViewerFeed(maxsize=8), from_start=True)
    follower2.poll()
    shown = list(feed._q.queue)  # every frame put, oldest first (maxsize 8 > 4 rows)
    assert [f.part_id for f in shown][-3:] == ["P1", "P2", "P3"]
    p2 = shown[-2]
    assert p2.decision == "reject" and p2.intensity.shape == (48, 64) and p2.dolp is not None
    np.testing.assert_allclose(p2.heatmap, heat, atol=1e-3)  # stored as float16
    assert shown[-3].reason == "passed parts keep no image" and shown[-3].heatmap is None
    assert p2.checks == {"highlight_fraction": 0.05, "noise_level": 1.2} and shown[-3].checks == {}
    assert p2.stats["parts"] == 3 and p2.stats["rejects"] == 1 and follower2.stats()["rejects"] == 2
    follower.close()
    follower2.close()
    station_log.close()


def test_view_command_runs_offscreen_and_names_a_missing_log(tmp_path: Path, monkeypatch, capsys) -> None:
    pytest.importorskip("pyqtgraph")
    monkeypatch.setenv("QT_QPA_PLATFORM", "offscreen")
    InspectionLog(tmp_path / "log.sqlite").close()
    assert main(["view", "--db", str(tmp_path / "log.sqlite"), "--seconds", "0.5"]) == 0
    assert main(["view", "--db", str(tmp_path / "nope.sqlite"), "--seconds", "0.5"]) == 2
    assert "nope.sqlite" in capsys.readouterr().err


def test_a_row_amended_after_it_was_shown_is_shown_again_as_amended(tmp_path: Path) -> None:
    """A PASS that went out late as a REJECT is amended in the log after the viewer showed it: the viewer kept
    showing it as passed."""
    station_log = InspectionLog(tmp_path / "log.sqlite")
    feed = ViewerFeed(maxsize=8)
    follower = LogFollower(tmp_path / "log.sqlite", feed)
    station_log.append([record("pass", "P1", score=0.1, threshold=0.5), record("pass", "P2", score=0.2,
                                                                                threshold=0.5)])
    assert follower.poll() == 2 and follower.stats()["rejects"] == 0
    row_id = station_log.last_id()
    station_log.amend_decision(row_id, "reject", "not answered in time: the PASS was not delivered")
    assert follower.poll() == 1
    assert follower.stats()["rejects"] == 1 and follower.stats()["parts"] == 2
    shown = feed.latest()
    assert (shown.part_id, shown.decision) == ("P2", "reject") and "not answered in time" in shown.reason
    assert follower.poll() == 0


def test_the_follower_reads_the_log_from_its_own_thread(tmp_path: Path) -> None:
    """`station view` opens the follower in the main thread and polls from another: every poll raised SQLite's
    "objects created in a thread can only be used in that same thread", and the viewer showed nothing."""
    import threading

    station_log = InspectionLog(tmp_path / "log.sqlite")
    feed = ViewerFeed(maxsize=8)
    follower = LogFollower(tmp_path / "log.sqlite", feed, from_start=True)
    station_log.append(record("pass", "P1", score=0.1, threshold=0.5))
    stop = threading.Event()
    thread = threading.Thread(target=follower.run, args=(stop, 0.02))
    thread.start()
    deadline, shown = time.monotonic() + 5, None
    while shown is None and time.monotonic() < deadline:
        time.sleep(0.02)
        shown = feed.latest()  # takes what is queued
    stop.set()
    thread.join()
    assert shown is not None and shown.part_id == "P1"


def test_a_reject_imaged_once_per_dome_segment_shows_the_whole_domes_priors(tmp_path: Path) -> None:
    """A part imaged once per dome segment keeps every frame (``raw``, ``raw_1``); the viewer shows the priors of
    their mean, as the station judged it, not those of the first half-lit frame."""
    from model.priors.api import compute_set_priors

    s0, s1, s2 = detailed_stokes(48, 64)
    lean = np.linspace(0.5, 1.5, 64, dtype=np.float32)[None, :]  # the halves of the dome, lit in turn
    raws = [(np.clip(stokes_to_mosaic(s0 * w, s1 * w, s2 * w), 0, 1) * 200).astype(np.uint8)
            for w in (lean, lean[:, ::-1])]
    image = RejectStore(tmp_path / "rejects").save("P1", 1, raws[0], None, later=(raws[1],))
    station_log = InspectionLog(tmp_path / "log.sqlite")
    follower = LogFollower(tmp_path / "log.sqlite", feed := ViewerFeed())
    station_log.append(record("reject", "P1", score=0.9, threshold=0.5, image_path=image))
    assert follower.poll() == 1
    shown = feed.latest()
    whole = compute_set_priors(raws, (0.0, 180.0), priors=("intensity",))["intensity"]
    np.testing.assert_allclose(shown.intensity, whole, atol=1e-6)
    follower.close()
    station_log.close()
