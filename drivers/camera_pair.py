"""Two cameras that image each part together, as one ``drivers.camera.Camera``.

A station with a second camera (a side camera looking level at the part beside the line camera looking down on it)
takes one frame from each per part. ``CameraPair`` triggers both (``trigger="software"``; on a line trigger both
cameras are wired to the part's pulse) and returns the first camera's frame with the second's as its ``companion``.
The station's timing rules (``station.loop``) read the first camera's frame; the pair keeps the two frames of one
part together by their host times:

- a second-camera frame completed more than ``max_skew_ms`` before the first camera's is an earlier part's (it came
  after its own part gave up on it): skipped, counted in ``unpaired``;
- one completed more than ``max_skew_ms`` after it is a later part's (the second camera missed this part's pulse):
  held for the next grab, and this grab raises ``CameraTimeout`` (the part has no second frame; the station rejects
  it, fail closed);
- no second frame within the grab's timeout: ``CameraTimeout``; a lost second camera: ``CameraLost``. Every message
  says which camera.

Frames without host times (0) are paired as they come. ``configure`` applies to the first camera; ``statistics`` is
the first camera's, ``second_statistics`` the second's.
"""

from __future__ import annotations

import dataclasses
import logging
import time

from drivers.camera import Camera, CameraBase, CameraConfig, CameraStatistics
from drivers.errors import CameraError, CameraTimeout
from drivers.frame import Frame

log = logging.getLogger(__name__)


def _named(exc: CameraError, name: str) -> CameraError:
    """``exc`` again, of the same class, its message starting with the camera's ``name``."""
    return type(exc)(f"{name}: {exc}")


class CameraPair(CameraBase):
    """See the module docstring. ``first`` and ``second`` are opened, started, stopped and closed together; the
    pair owns both."""

    def __init__(self, first: Camera, second: Camera, max_skew_ms: float, second_name: str = "second camera") -> None:
        super().__init__(first.config)
        if max_skew_ms <= 0:
            raise ValueError(f"max_skew_ms must be > 0, got {max_skew_ms}")
        self.first, self.second = first, second
        self.max_skew_ms = max_skew_ms
        self.second_name = second_name
        self.unpaired = 0
        """Second-camera frames skipped as an earlier part's."""
        self._held: Frame | None = None

    def open(self) -> None:
        self.first.open()
        try:
            self.second.open()
        except Exception:
            self.first.close()
            raise

    def configure(self, config: CameraConfig) -> None:
        self.first.configure(config)
        self.config = config

    def start(self) -> None:
        self.first.start()
        try:
            self.second.start()
        except CameraError as exc:
            self.first.stop()
            raise _named(exc, self.second_name) from None

    def trigger(self) -> None:
        self.first.trigger()
        try:
            self.second.trigger()
        except CameraError as exc:
            raise _named(exc, self.second_name) from None

    def grab(self, timeout_ms: int | None = None) -> Frame:
        timeout_ms = timeout_ms if timeout_ms is not None else self.config.timeout_ms
        deadline = time.perf_counter() + timeout_ms / 1e3
        frame = self.first.grab(timeout_ms)
        return dataclasses.replace(frame, companion=self._companion(frame, deadline))

    def _companion(self, frame: Frame, deadline: float) -> Frame:
        """The second camera's frame of ``frame``'s part (module docstring)."""
        while True:
            if self._held is not None:
                other, self._held = self._held, None
            else:
                remaining_ms = max(1, int(1e3 * (deadline - time.perf_counter())))
                try:
                    other = self.second.grab(remaining_ms)
                except CameraError as exc:
                    raise _named(exc, self.second_name) from None
            if frame.host_timestamp_ns <= 0 or other.host_timestamp_ns <= 0:
                return other
            skew_ms = (other.host_timestamp_ns - frame.host_timestamp_ns) / 1e6
            if skew_ms > self.max_skew_ms:
                self._held = other
                raise CameraTimeout(f"{self.second_name}: its next frame ({other.frame_id}) came {skew_ms:.0f} ms "
                                    f"after the first camera's ({frame.frame_id}), over {self.max_skew_ms:.0f} ms: it "
                                    "missed this part; the frame is kept for the next part")
            if skew_ms >= -self.max_skew_ms:
                return other
            self.unpaired += 1
            log.warning("%s: frame %d came %.0f ms before the first camera's frame %d: an earlier part's, skipped",
                        self.second_name, other.frame_id, -skew_ms, frame.frame_id)

    def stop(self) -> None:
        self.first.stop()
        self.second.stop()

    def close(self) -> None:
        self.first.close()
        self.second.close()

    def statistics(self) -> CameraStatistics:
        return self.first.statistics()

    def second_statistics(self) -> CameraStatistics:
        return self.second.statistics()
