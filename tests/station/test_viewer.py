"""The Qt viewer offscreen: a real window grabbed to PNG, its content checked; the feed never blocks."""

from __future__ import annotations

import os
import threading

import numpy as np
import pytest

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
pytest.importorskip("pyqtgraph")

from station.viewer import ViewerFeed, ViewFrame, create_window, heatmap_lut


@pytest.fixture(scope="module")
def app():
    from pyqtgraph.Qt import QtWidgets

    return QtWidgets.QApplication.instance() or QtWidgets.QApplication([])


def frame(decision: str, anomaly: bool, part: str = "P1") -> ViewFrame:
    h, w = 96, 128
    heat = np.zeros((h, w), np.float32)
    if anomaly:
        heat[30:60, 40:80] = 1.0
    y, x = np.mgrid[0:h, 0:w]
    return ViewFrame(part_id=part, decision=decision, score=0.9 if anomaly else 0.1, threshold=0.5,
                     intensity=np.full((h, w), 0.3, np.float32), dolp=(x / w).astype(np.float32),
                     aolp=(np.pi * y / h).astype(np.float32), normal=np.dstack([0 * x, 0 * x, 1 + 0 * x]),
                     heatmap=heat, stats={"parts": 10, "parts_per_s": 12.5},
                     checks={"noise_level": 1.5, "highlight_fraction": 0.04, "edge_bend": -0.4,
                             "unseen_fraction": 0.023, "turn_deg": -7.46, "look_level": 0.314})


def grab(app, window, tmp_path, name):
    for _ in range(5):
        app.processEvents()
    path = tmp_path / name
    assert window.grab().save(str(path))
    from pyqtgraph.Qt import QtGui

    img = QtGui.QImage(str(path)).convertToFormat(QtGui.QImage.Format.Format_RGB888)
    ptr = img.constBits()
    arr = np.frombuffer(ptr, np.uint8, count=img.sizeInBytes()).reshape(img.height(), img.bytesPerLine())
    return arr[:, : img.width() * 3].reshape(img.height(), img.width(), 3).copy()


def red_pixels(rgb: np.ndarray) -> int:
    r, g, b = (rgb[..., i].astype(int) for i in range(3))
    return int(((r > 150) & (g < 80) & (b < 80)).sum())


def green_pixels(rgb: np.ndarray) -> int:
    r, g, b = (rgb[..., i].astype(int) for i in range(3))
    return int(((g > 110) & (r < 60) & (b < 80)).sum())


def test_reject_shows_red_badge_and_heatmap_pass_shows_green(app, tmp_path):
    feed = ViewerFeed()
    window = create_window(feed)
    window.resize(900, 600)
    window.show()
    feed.put(frame("pass", anomaly=False))
    window.refresh()
    ok = grab(app, window, tmp_path, "pass.png")
    feed.put(frame("reject", anomaly=True, part="P2"))
    window.refresh()
    bad = grab(app, window, tmp_path, "reject.png")
    assert window.badge.text() == "REJECT" and "part P2" in window.stats.text()
    # the model's frame checks
    assert ("noise level 1.50  highlights 4 %  edge bend -0.40  outside view 2.3 %  turn -7.5 deg  look 0.31"
            in window.stats.text())
    assert green_pixels(ok) > 2000 and red_pixels(ok) < 200
    # the red badge plus an opaque red heatmap patch over the intensity image
    assert red_pixels(bad) > red_pixels(ok) + 4000
    assert feed.shown == 2


def test_feed_keeps_newest_and_never_blocks_the_producer():
    feed = ViewerFeed(maxsize=2)
    t = threading.Thread(target=lambda: [feed.put(frame("pass", False, part=str(i))) for i in range(500)])
    t.start()
    t.join(timeout=5)
    assert not t.is_alive()
    latest = feed.latest()
    assert latest is not None and latest.part_id == "499"
    assert feed.skipped == 498 and feed.latest() is None


def test_heatmap_is_transparent_at_zero_and_opaque_at_one():
    lut = heatmap_lut()
    assert lut[0, 3] == 0 and lut[-1, 3] == 255 and (np.diff(lut[:, 3].astype(int)) >= 0).all()


@pytest.mark.slow
def test_viewer_soak_thousands_of_frames(app):
    # PySide6 6.12.0 died after ~1,100 signal emits (docs/platform-facts.md): thousands of frames show it.
    feed = ViewerFeed()
    window = create_window(feed)
    window.show()
    for i in range(3000):
        feed.put(frame("reject" if i % 7 == 0 else "pass", anomaly=i % 7 == 0, part=str(i)))
        window.refresh()
        app.processEvents()
    assert feed.shown == 3000


def test_a_segment_models_tilt_shows_where_the_normal_would(app, tmp_path):
    """A part judged on a frame per dome segment has no normal prior; its tilt shows in that panel, a part leaning
    toward +x on one side of the map's colours and toward -x on the other, and the label says which it is."""
    import dataclasses

    feed = ViewerFeed()
    window = create_window(feed)
    window.resize(900, 600)
    window.show()
    tilted = dataclasses.replace(frame("pass", anomaly=False), normal=None, heatmap=None)
    shots = []
    for lean in (0.8, -0.8):
        feed.put(dataclasses.replace(tilted, tilt=np.full((96, 128), lean, np.float32)))
        window.refresh()
        shots.append(grab(app, window, tmp_path, f"tilt{lean}.png"))
        assert window.labels["normal"].toPlainText() == "tilt toward +x [-1, 1]"
    # the panel's colours differ between the two leans (the rest of the window is the same)
    assert np.abs(shots[0].astype(int) - shots[1].astype(int)).sum(-1).astype(bool).sum() > 5000
    feed.put(frame("pass", anomaly=False))
    window.refresh()
    assert window.labels["normal"].toPlainText() == "normal (n+1)/2"
