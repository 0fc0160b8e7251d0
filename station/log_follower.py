"""Attach a viewer to a station that is already running, through its inspection log.

The station writes every part to SQLite in WAL mode, so another process can read the log while it is written.
``LogFollower`` polls for rows newer than the last one seen (and for recent rows whose decision was amended) and
turns each into a ``ViewFrame``: rejected parts whose raw mosaic and heatmap were saved (``[log] save_rejects``,
``station.reject_store``) show their images (priors recomputed from the mosaic; for a part imaged once per dome
segment, from its frames' mean, the whole dome's, as the station judged it); other parts show the decision and
statistics over a blank image, since the station keeps no image of them. Statistics come from the log: counts,
reject rate, latency p50/p99 of the last ``window`` parts.
"""

from __future__ import annotations

import logging
import threading
from collections import Counter, deque
from pathlib import Path
from typing import Any

import numpy as np

from model.draem.frame_checks import FRAME_CHECKS
from station.decision import Verdict
from station.inspection_log import InspectionLog
from station.viewer import ViewerFeed, ViewFrame

log = logging.getLogger(__name__)


class LogFollower:
    """Tail ``db`` into ``feed``; ``from_start=False`` shows only parts logged after attaching."""

    RECHECK = 256
    """The newest rows read again at every poll for amended decisions (an amendment comes within seconds)."""

    def __init__(self, db: str | Path, feed: ViewerFeed, *, layout: str = "imx250mzr", from_start: bool = False,
                 window: int = 200) -> None:
        self.log = InspectionLog(db, readonly=True)
        self.feed, self.layout = feed, layout
        self.last_id = 0 if from_start else self.log.last_id()
        self.counts: Counter[str] = Counter()
        self.latencies: deque[float] = deque(maxlen=window)
        self.blank = np.zeros((64, 64), np.float32)
        self.shown_images = 0
        self.shown: dict[int, str] = {}  # row id -> decision shown, the newest RECHECK rows
        self.warned: set[str] = set()  # kinds of error already logged by ``run``

    def poll(self) -> int:
        """Put a ViewFrame for every new row on the feed, and again for each of the last ``RECHECK`` rows whose
        decision changed since it was shown (a PASS the PLC link sent late as a REJECT is amended after its row was
        written); returns how many rows were new or changed."""
        n = 0
        for row in list(self.log.rows(after_id=max(0, self.last_id - self.RECHECK))):
            before = self.shown.get(row["id"])
            if row["id"] <= self.last_id and before in (None, row["decision"]):
                continue  # seen and unchanged, or shown before this follower attached
            if before is not None:
                self.counts[before] -= 1
            else:
                self.last_id = max(self.last_id, row["id"])
                if row["total_ms"] is not None:
                    self.latencies.append(row["total_ms"])
            self.counts[row["decision"]] += 1
            self.shown[row["id"]] = row["decision"]
            while len(self.shown) > self.RECHECK:
                self.shown.pop(next(iter(self.shown)))
            self.feed.put(self._frame(row))
            n += 1
        return n

    def stats(self) -> dict[str, float]:
        parts = sum(self.counts.values())
        lat = np.array(self.latencies) if self.latencies else np.zeros(1)
        c = self.counts
        return {"parts": parts, "rejects": c[Verdict.REJECT], "empty": c[Verdict.EMPTY],
                "not_inspected": c[Verdict.NOT_INSPECTED],
                # of judged parts, as station report: empty frames (free run, between parts) would dilute it
                "reject_rate": c[Verdict.REJECT] / max(c[Verdict.PASS] + c[Verdict.REJECT], 1),
                "p50_ms": float(np.percentile(lat, 50)),
                "p99_ms": float(np.percentile(lat, 99))}

    def _frame(self, row: dict[str, Any]) -> ViewFrame:
        maps: dict[str, np.ndarray | None] = {"intensity": self.blank}
        heatmap = None
        reason = row["reason"]
        if row["image_path"]:
            try:
                maps, heatmap = self._images(row["image_path"])
                self.shown_images += 1
            except (OSError, ValueError, KeyError) as exc:  # deleted by retention, or unreadable
                reason = f"{reason or ''} (image {row['image_path']} unreadable: {exc})"
        elif row["decision"] == Verdict.PASS:
            reason = "passed parts keep no image"
        return ViewFrame(str(row["part_id"]), row["decision"], row["score"], row["threshold"], maps["intensity"],
                         maps.get("dolp"), maps.get("aolp"), None, heatmap, reason, self.stats(),
                         {k: row[k] for k in FRAME_CHECKS if row.get(k) is not None})

    def _images(self, path: str) -> tuple[dict[str, np.ndarray | None], np.ndarray | None]:
        from model.priors.api import compute_set_priors

        with np.load(path) as f:
            raws = [f["raw"]] + [f[f"raw_{k}"] for k in range(1, len(f.files)) if f"raw_{k}" in f]
            heatmap = f["heatmap"].astype(np.float32) if "heatmap" in f else None
        p = compute_set_priors(raws, None, self.layout, priors=("intensity", "dolp", "aolp"))
        if heatmap is not None and heatmap.shape != p["intensity"].shape:
            heatmap = None  # saved by another demosaic resolution: do not misplace it
        return {"intensity": p["intensity"], "dolp": p["dolp"], "aolp": p["aolp"]}, heatmap

    def run(self, stop: threading.Event, poll_s: float = 0.2) -> None:
        """Poll until ``stop`` is set (a background thread of the viewer)."""
        while not stop.is_set():
            try:
                self.poll()
            except Exception as exc:  # a viewer must not die of one bad row; say it once per kind
                if type(exc).__name__ not in self.warned:
                    self.warned.add(type(exc).__name__)
                    log.warning("log follower: %s: %s", type(exc).__name__, exc)
            stop.wait(poll_s)

    def close(self) -> None:
        self.log.close()
