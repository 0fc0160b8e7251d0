"""The model on a thread of its own, so that no part waits on it past its deadline.

The loop hands a frame over and waits at most until the part's deadline. A model that has not answered by then (a
stall: swapped-out memory, a stuck BLAS thread, a device that stopped answering) does not hold up the loop: the part
is rejected on time, and the parts that arrive while the model is still busy are rejected at once ("model busy"),
since it judges one frame at a time. Its late answer is logged and dropped. A model that never returns shows as
"busy" part after part; the loop stops the station after ``station.loop.MAX_MODEL_BUSY_PARTS`` of them.

The thread is a daemon: a hung model does not keep the process alive after the station stops.
"""

from __future__ import annotations

import logging
import queue
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from drivers.frame import Frame
from station.inspector import Inspection

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class NoAnswer:
    """Why the model gave no inspection for a part: ``busy`` (still on an earlier part, not started) or timed out."""

    reason: str
    busy: bool


class ModelThread:
    """Runs ``inspect`` (``Inspector.inspect``) on its own thread, one part's frames at a time; one caller thread."""

    def __init__(self, inspect: Callable[[Sequence[Frame]], Inspection]) -> None:
        self._inspect = inspect
        self._jobs: queue.SimpleQueue[tuple[str, Sequence[Frame]] | None] = queue.SimpleQueue()
        self._idle = threading.Event()
        self._idle.set()
        self._result: Inspection | None = None
        self._current = ("", 0.0)  # (part id, perf_counter) of the last hand-over: the caller's alone to write
        self._abandoned = False  # the caller stopped waiting for the current part
        threading.Thread(target=self._serve, name="model", daemon=True).start()

    def inspect(self, part_id: str, frames: Sequence[Frame], deadline: float) -> Inspection | NoAnswer:
        """The inspection of a part's ``frames`` (one, or one per dome segment) if the model returns by ``deadline``
        (``time.perf_counter()``), else why not. A part is not handed over while the model is still on an earlier
        one."""
        if not self._idle.is_set():
            busy_id, since = self._current
            return NoAnswer(f"model busy: still on part {busy_id} after "
                            f"{1e3 * (time.perf_counter() - since):.0f} ms", busy=True)
        self._idle.clear()
        self._abandoned = False
        self._current = (part_id, time.perf_counter())
        self._jobs.put((part_id, frames))
        if self._idle.wait(max(0.0, deadline - time.perf_counter())):
            result, self._result = self._result, None
            assert result is not None
            return result
        self._abandoned = True
        return NoAnswer(f"the model had not answered {1e3 * (time.perf_counter() - self._current[1]):.0f} ms "
                        "after the hand-over", busy=False)

    def close(self) -> None:
        """End the thread once it is done with its frame (a hung model's thread stays, as a daemon)."""
        self._jobs.put(None)

    def _serve(self) -> None:
        while (job := self._jobs.get()) is not None:
            part_id, frames = job
            t = time.perf_counter()
            try:
                result = self._inspect(frames)
            except BaseException as exc:  # inspect reports its own errors; anything else must not kill the thread
                result = Inspection(error=f"frame {frames[0].frame_id}: inspection failed: {type(exc).__name__}: "
                                          f"{exc}")
            if self._abandoned:
                log.warning("model answered part %s after %.0f ms, past its deadline: answer dropped (the part "
                            "was rejected)", part_id, 1e3 * (time.perf_counter() - t))
            self._result = result
            self._idle.set()
