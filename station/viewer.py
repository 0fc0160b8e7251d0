"""A minimal live viewer (pyqtgraph on Qt 6): intensity with the anomaly heatmap, DoLP, AoLP, normals, the
decision badge and running statistics.

The GUI thread never waits on the camera or the model: the station puts ``ViewFrame``s into a ``ViewerFeed``
(a bounded queue that keeps the newest) and the window pulls the newest one on a Qt timer signal. The heatmap
has a fixed scale, transparent at 0 and fully opaque at 1, so a good part looks clean rather than rescaled.
"""

from __future__ import annotations

import queue
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from model.draem.frame_checks import UNSEEN_LIMIT
from station.decision import Verdict

DISPLAY_HZ = 30.0


@dataclass(frozen=True)
class ViewFrame:
    """What one inspected part shows. Arrays are (H, W) float32 in the priors' units (``model.priors``),
    ``normal`` (H, W, 3) unit vectors, ``tilt`` the surface's tilt toward +x in [-1, 1] (``tilt_x``, a model that
    reads a frame per dome segment: shown where the normal would be), ``heatmap`` anomaly probability in [0, 1]."""

    part_id: str
    decision: Verdict | str
    """A ``Verdict`` (the live station) or its value (a row of the log, ``station.log_follower``)."""
    score: float | None
    threshold: float | None
    intensity: np.ndarray
    dolp: np.ndarray | None = None
    aolp: np.ndarray | None = None
    normal: np.ndarray | None = None
    heatmap: np.ndarray | None = None
    reason: str | None = None
    stats: dict[str, float] = field(default_factory=dict)
    """Running statistics shown under the badge, e.g. parts, rejects, parts_per_s, p99_ms."""
    checks: dict[str, float] = field(default_factory=dict)
    """The model's frame checks of this part (``model.draem.frame_checks.FRAME_CHECKS``), shown beside its score."""
    tilt: np.ndarray | None = None


class ViewerFeed:
    """Hand-over from the station thread to the GUI: ``put`` never blocks and keeps only the newest frames."""

    def __init__(self, maxsize: int = 2) -> None:
        self._q: queue.Queue[ViewFrame] = queue.Queue(maxsize=maxsize)
        self.shown = 0
        self.skipped = 0

    def put(self, frame: ViewFrame) -> None:
        while True:
            try:
                self._q.put_nowait(frame)
                return
            except queue.Full:
                try:
                    self._q.get_nowait()
                    self.skipped += 1
                except queue.Empty:
                    pass

    def latest(self) -> ViewFrame | None:
        frame = None
        while True:
            try:
                frame = self._q.get_nowait()
            except queue.Empty:
                return frame


def heatmap_lut() -> np.ndarray:
    """RGBA lookup table (256, 4): yellow to red, alpha rising from 0 (no anomaly) to 255 (certain anomaly)."""
    t = np.linspace(0.0, 1.0, 256)
    lut = np.empty((256, 4), np.uint8)
    lut[:, 0] = 255
    lut[:, 1] = np.round(255 * (1 - t) * 0.9).astype(np.uint8)
    lut[:, 2] = 0
    lut[:, 3] = np.round(255 * np.clip(t * 1.25, 0, 1)).astype(np.uint8)
    return lut


def normal_to_rgb(normal: np.ndarray) -> np.ndarray:
    """Unit normals (H, W, 3) -> uint8 RGB, the usual (n + 1) / 2 encoding."""
    return np.clip((np.nan_to_num(normal) + 1.0) * 127.5, 0, 255).astype(np.uint8)


def create_window(feed: ViewerFeed):  # -> ViewerWindow (Qt types only exist after import)
    """Build the viewer window for ``feed``. Needs a QApplication (see ``run_viewer``)."""
    import pyqtgraph as pg
    from pyqtgraph.Qt import QtCore, QtWidgets

    class ViewerWindow(QtWidgets.QWidget):
        def __init__(self) -> None:
            super().__init__()
            self.setWindowTitle("Polar-Ano Station")
            self.resize(1100, 720)
            layout = QtWidgets.QGridLayout(self)
            self.graphics = pg.GraphicsLayoutWidget()
            layout.addWidget(self.graphics, 0, 0, 1, 2)
            self.images: dict[str, pg.ImageItem] = {}
            self.labels: dict[str, pg.TextItem] = {}
            for i, (name, title) in enumerate([("intensity", "intensity + anomaly"), ("dolp", "DoLP [0, 1]"),
                                               ("aolp", "AoLP [0, pi) (cyclic)"), ("normal", "normal (n+1)/2")]):
                view = self.graphics.addViewBox(row=i // 2, col=i % 2, lockAspect=True, invertY=True)
                view.setMouseEnabled(False, False)
                self.graphics.ci.layout.setRowStretchFactor(i // 2, 1)
                item = pg.ImageItem(axisOrder="row-major")
                view.addItem(item)
                self.images[name] = item
                label = pg.TextItem(title, color="w", anchor=(0, 0), fill=(0, 0, 0, 160))
                view.addItem(label, ignoreBounds=True)
                self.labels[name] = label
                if name == "intensity":
                    self.heat = pg.ImageItem(axisOrder="row-major")
                    self.heat.setLookupTable(heatmap_lut())
                    self.heat.setLevels((0.0, 1.0))
                    view.addItem(self.heat)
            self.images["dolp"].setColorMap(pg.colormap.get("viridis"))
            self.images["aolp"].setColorMap(pg.colormap.get("CET-C2"))
            self.badge = QtWidgets.QLabel("WAITING")
            self.badge.setAlignment(QtCore.Qt.AlignmentFlag.AlignCenter)
            self.badge.setMinimumWidth(220)
            self._style_badge("WAITING")
            self.stats = QtWidgets.QLabel("")
            layout.addWidget(self.badge, 1, 0)
            layout.addWidget(self.stats, 1, 1)
            self.timer = QtCore.QTimer(self)
            self.timer.timeout.connect(self.refresh)
            self.timer.start(int(1000 / DISPLAY_HZ))

        def _style_badge(self, decision: Verdict | str) -> None:
            color = {Verdict.PASS: "#1b8a2f", Verdict.REJECT: "#c0161c"}.get(decision, "#666666")
            self.badge.setStyleSheet(f"background:{color}; color:white; font-size:28px; font-weight:bold;"
                                     "padding:8px; border-radius:6px;")

        def refresh(self) -> None:
            frame = feed.latest()
            if frame is not None:
                self.show_frame(frame)

        def show_frame(self, f: ViewFrame) -> None:
            self.images["intensity"].setImage(f.intensity, levels=(0.0, max(float(f.intensity.max()), 1e-6)))
            if f.heatmap is not None:
                self.heat.setImage(f.heatmap, levels=(0.0, 1.0))
            self.heat.setVisible(f.heatmap is not None)
            if f.dolp is not None:
                self.images["dolp"].setImage(f.dolp, levels=(0.0, 1.0))
            if f.aolp is not None:
                self.images["aolp"].setImage(f.aolp, levels=(0.0, np.pi))
            if f.normal is not None:
                self.images["normal"].setLookupTable(None)
                self.images["normal"].setImage(normal_to_rgb(f.normal))
                self.labels["normal"].setText("normal (n+1)/2")
            elif f.tilt is not None:  # the same panel: a diverging map, leaning toward +x in red
                self.images["normal"].setColorMap(pg.colormap.get("CET-D1"))
                self.images["normal"].setImage(f.tilt, levels=(-1.0, 1.0))
                self.labels["normal"].setText("tilt toward +x [-1, 1]")
            self.badge.setText(f.decision.upper().replace("_", " "))
            self._style_badge(f.decision)
            score = "" if f.score is None else f"score {f.score:.3f}"
            if f.threshold is not None:
                score += f" / threshold {f.threshold:.3f}"
            if "noise_level" in f.checks:
                score += f"  noise level {f.checks['noise_level']:.2f}"
            if "highlight_fraction" in f.checks:
                score += f"  highlights {100 * f.checks['highlight_fraction']:.0f} %"
            if "edge_bend" in f.checks:
                score += f"  edge bend {f.checks['edge_bend']:+.2f}"
            if "edge_step" in f.checks:
                score += f"  edge step {f.checks['edge_step']:.2f}"
            if f.checks.get("unseen_fraction", 0.0) > UNSEEN_LIMIT:
                score += f"  outside view {100 * f.checks['unseen_fraction']:.2g} %"
            if "turn_deg" in f.checks:
                score += f"  turn {f.checks['turn_deg']:+.1f} deg"
            if "look_level" in f.checks:
                score += f"  look {f.checks['look_level']:.2f}"
            stats = "  ".join(f"{k} {v:.4g}" for k, v in f.stats.items())
            self.stats.setText(f"part {f.part_id}  {score}\n{f.reason or ''}\n{stats}")
            feed.shown += 1

    return ViewerWindow()


def run_viewer(feed: ViewerFeed, done: Callable[[], bool] | None = None) -> int:
    """Run the Qt event loop with a viewer of ``feed`` until the window closes, or until ``done()`` turns true
    (polled every 0.2 s; e.g. the station finished its ``--frames``). Call from the main thread."""
    from pyqtgraph.Qt import QtCore, QtWidgets

    app = QtWidgets.QApplication.instance() or QtWidgets.QApplication([])
    window = create_window(feed)
    window.show()
    if done is not None:
        timer = QtCore.QTimer(window)
        timer.timeout.connect(lambda: window.close() if done() else None)
        timer.start(200)
    return app.exec()
