"""A second camera's look at each part, beside the first camera's: ``[second_camera]`` in ``station.toml``.

The line camera looks down on the part and sees its top face; the front faces, which mirror the belt, it sees
poorly. A side camera at belt level under a flat dome sees them square-on (docs/results/2026-11-30-side-view.md).
Each part then has two frames (``drivers.camera_pair.CameraPair``), two models, two presence checks and two
thresholds; the part gets one answer and one log row:

- ``PairInspector`` judges the first camera's frame with the first inspector and its ``companion`` (the second
  camera's frame of the same part) with the second, one after the other, and returns the first camera's
  ``Inspection`` with the second's as its ``second``. A part with no second frame has an error there.
- ``station.decision.join`` makes the part's decision (the loop decides each camera on its own threshold first):
  either camera's reject rejects, with its reason; a part neither sees is empty; a part one camera sees and the
  other does not is rejected.

The two thresholds come from one budget of good parts rejected, split between the cameras on validation
(``model.draem.camera_split``): each camera's threshold alone would reject up to the whole budget, and the two
together up to twice it. ``station split`` sets them (docs/station.md, "A second camera").
"""

from __future__ import annotations

from collections.abc import Sequence

from drivers.frame import Frame
from station.inspector import Detector, Inspection, Inspector

SECOND_NAME = "second camera"
"""How rows and messages name the second camera."""


class PairInspector:
    """Two inspectors, one per camera, as one for the loop (``Inspector.inspect``'s protocol). ``detector`` is the
    first camera's (its model id and threshold are the row's ``model_id`` and ``threshold``)."""

    def __init__(self, first: Inspector, second: Inspector) -> None:
        if second.segments:
            raise ValueError("the second camera takes one frame per part: its model must not read dome segments")
        self.first, self.second = first, second

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
        them) and the first frame's ``companion``. The result's stage times are both cameras' together."""
        frames = (frames,) if isinstance(frames, Frame) else tuple(frames)
        result = self.first.inspect(frames)
        companion = frames[0].companion if frames else None
        if companion is None:
            second = Inspection(error=f"no frame from the {SECOND_NAME}")
        else:
            second = self.second.inspect(companion)
        for stage, ms in second.timings_ms.items():
            result.timings_ms[stage] = result.timings_ms.get(stage, 0.0) + ms
        result.second = second
        return result
