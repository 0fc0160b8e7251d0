"""A second camera's look at each part, beside the first camera's: ``[second_camera]`` in ``station.toml``.

The line camera looks down on the part and sees its top face; the front faces, which mirror the belt, it sees
poorly. A side camera at belt level under a flat dome sees them square-on (docs/results/2026-11-30-side-view.md).
Each part then has two frames (``drivers.camera_pair.CameraPair``), two models, two presence checks and two
thresholds; the part gets one answer and one log row:

- ``PairInspector`` judges the first camera's frame with the first inspector and its ``companion`` (the second
  camera's frame of the same part) with the second, at the same time on a thread of its own (``parallel``; or one
  after the other), and returns the first camera's ``Inspection`` with the second's as its ``second``. A part with
  no second frame has an error there.
- ``station.decision.join`` makes the part's decision (the loop decides each camera on its own threshold first):
  either camera's reject rejects, with its reason; a part neither sees is empty; a part one camera sees and the
  other does not is rejected.

The two thresholds come from one budget of good parts rejected, split between the cameras on validation
(``model.draem.camera_split``): each camera's threshold alone would reject up to the whole budget, and the two
together up to twice it. ``station split`` sets them (docs/second-camera.md).
"""

from __future__ import annotations

from collections.abc import Sequence
from concurrent.futures import ThreadPoolExecutor

from drivers.frame import Frame
from station.decision import SECOND_NAME
from station.inspector import Detector, Inspection, Inspector

__all__ = ["SECOND_NAME", "PairInspector"]


class PairInspector:
    """Two inspectors, one per camera, as one for the loop (``Inspector.inspect``'s protocol). ``detector`` is the
    first camera's (its model id and threshold are the row's ``model_id`` and ``threshold``). ``parallel``: the
    second camera's frame is judged on a thread of its own while the first's is judged (the heavy steps, numpy,
    OpenCV and torch, release the interpreter's lock); else after it."""

    def __init__(self, first: Inspector, second: Inspector, parallel: bool = True) -> None:
        if second.segments:
            raise ValueError("the second camera takes one frame per part: its model must not read dome segments")
        self.first, self.second = first, second
        self.parallel = parallel
        self._pool: ThreadPoolExecutor | None = None
        """The second camera's thread (``parallel``): made at the first part, ended by ``close``."""

    @property
    def detector(self) -> Detector:
        return self.first.detector

    @property
    def slow_priors_ms(self) -> float | None:
        return self.first.slow_priors_ms

    @slow_priors_ms.setter
    def slow_priors_ms(self, ms: float | None) -> None:
        self.first.slow_priors_ms = self.second.slow_priors_ms = ms

    def inspect(self, frames: Frame | Sequence[Frame]) -> Inspection:
        """Judge one part on both cameras' frames: the first camera's (``frames``, as ``Inspector.inspect`` takes
        them) and the first frame's ``companion``. The result's stage times are both cameras' together (in parallel:
        the longer of the two)."""
        frames = (frames,) if isinstance(frames, Frame) else tuple(frames)
        companion = frames[0].companion if frames else None
        pending = None
        if companion is not None and self.parallel:
            if self._pool is None:
                self._pool = ThreadPoolExecutor(1, thread_name_prefix="second-camera")
            pending = self._pool.submit(self.second.inspect, companion)
        result = self.first.inspect(frames)
        if companion is None:
            second = Inspection(error=f"no frame from the {SECOND_NAME}")
        elif pending is not None:
            try:
                second = pending.result()
            except Exception as exc:  # Inspector.inspect returns its errors; anything else still rejects the part
                second = Inspection(error=f"{type(exc).__name__}: {exc}")
        else:
            second = self.second.inspect(companion)
        for stage, ms in second.timings_ms.items():  # each stage's time for the part: the two cameras' together,
            mine = result.timings_ms.get(stage, 0.0)  # or the longer of the two when they ran at the same time
            result.timings_ms[stage] = max(mine, ms) if pending is not None else mine + ms
        result.second = second
        return result

    def close(self) -> None:
        """End the second camera's thread once it is done with its frame (the loop calls this when a run ends; a
        later part makes a new one). Does not wait: a hung second model keeps its thread, as the model thread does."""
        pool, self._pool = self._pool, None
        if pool is not None:
            pool.shutdown(wait=False, cancel_futures=True)
        self.first.close()
        self.second.close()
