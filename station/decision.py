"""Pass, reject or empty, failing closed: a part that cannot be judged is rejected, and the reason says why.

"empty" (no part in view, from ``station.presence``) is not a judgement of a part: what the PLC is told about it
is the loop's business (``station.loop``: REJECT when a part was announced, nothing in free run).

The decision values are ``Verdict`` (re-exported from ``drivers.line_io``, where the PLC protocol and the station
can both import it); the station imports it from here."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from drivers.line_io import Verdict

__all__ = ["MAX_INVALID_FRACTION", "SECOND_NAME", "Decision", "Verdict", "decide", "join", "late"]

MAX_INVALID_FRACTION = 0.01
"""The share of a frame's pixels that may be invalid (NaN/Inf, out of range) for the part to be judged."""


@dataclass(frozen=True)
class Decision:
    decision: Verdict
    """PASS, REJECT or EMPTY (NOT_INSPECTED is the loop's, for a frame it dropped)."""
    reason: str | None = None
    """Why a part was rejected or skipped as empty; None for a pass."""


def late(elapsed_ms: float, cycle_time_ms: float, when: str = "") -> Decision:
    """Reject for time: ``elapsed_ms`` since the part's trigger reached the host is over ``cycle_time_ms``;
    ``when`` says at which step the part ran out of time (the one wording of every late reject)."""
    return Decision(Verdict.REJECT, f"not judged in time: {elapsed_ms:.1f} ms > cycle time {cycle_time_ms:.1f} ms"
                                    + (f" ({when})" if when else ""))


def decide(score: float | None, threshold: float, *, elapsed_ms: float | None = None,
           cycle_time_ms: float | None = None, error: str | None = None,
           invalid_fraction: float = 0.0, max_invalid_fraction: float = MAX_INVALID_FRACTION,
           empty: str | None = None, found: Sequence[str] = ()) -> Decision:
    """Decide one part. In order, each of these rejects with its reason: an ``error`` in an earlier stage;
    more than ``max_invalid_fraction`` of the input pixels invalid (NaN/Inf, out of range). Then ``empty`` (the
    presence check's reason, when it found no part) gives EMPTY with that reason. Then each of these rejects:
    a missing, non-finite or negative score (scores are probabilities) or a non-finite threshold; judgement later
    than the cycle time budget; ``score > threshold``, its reason followed by ``found``: what the model's frame checks
    found beyond their limits (``model.draem.frame_checks.beyond_limits``: a part bent, a frame unlike the model's
    line), so the row says why a part with no hotspot scored high. Otherwise pass. A frame whose pixels are unusable is
    rejected rather than called empty: its emptiness is not known. (A NaN threshold would pass every part:
    ``score > NaN`` is False.)"""
    if error:
        return Decision(Verdict.REJECT, f"not judged: {error}")
    if invalid_fraction > max_invalid_fraction:
        return Decision(Verdict.REJECT, f"not judged: {100 * invalid_fraction:.2f} % of input pixels invalid "
                                        f"(limit {100 * max_invalid_fraction:.2f} %)")
    if empty is not None:
        return Decision(Verdict.EMPTY, empty)
    if score is None or not math.isfinite(score) or score < 0.0:
        return Decision(Verdict.REJECT, f"not judged: model score is {score}")
    if threshold is None or not math.isfinite(threshold):
        return Decision(Verdict.REJECT, f"not judged: threshold is {threshold}")
    if elapsed_ms is not None and cycle_time_ms is not None and elapsed_ms > cycle_time_ms:
        return late(elapsed_ms, cycle_time_ms)
    if score > threshold:
        return Decision(Verdict.REJECT, "; ".join((f"score {score:.4f} > threshold {threshold:.4f}", *found)))
    return Decision(Verdict.PASS)


SECOND_NAME = "second camera"
"""How rows, the PLC's reasons and messages name a station's second camera (``station.second_camera``)."""


def join(first: Decision, second: Decision, second_name: str = SECOND_NAME) -> Decision:
    """One part's decision from its two cameras' (``station.second_camera``), failing closed. A reject by either
    rejects, with both reasons when both reject (the second's after ``second_name``). EMPTY only when neither camera
    sees a part. A part one camera sees and the other does not cannot be judged (misplaced, or a view the check cannot
    read): rejected, naming the camera that saw none. Otherwise pass."""
    named = f"{second_name}: {second.reason}"
    if first.decision == Verdict.REJECT and second.decision == Verdict.REJECT:
        return Decision(Verdict.REJECT, f"{first.reason}; {named}")
    if first.decision == Verdict.REJECT:
        return first
    if second.decision == Verdict.REJECT:
        return Decision(Verdict.REJECT, named)
    if first.decision == Verdict.EMPTY and second.decision == Verdict.EMPTY:
        return Decision(Verdict.EMPTY, f"{first.reason}; {named}")
    if first.decision == Verdict.EMPTY:
        return Decision(Verdict.REJECT, f"not judged: the first camera sees no part ({first.reason}), the "
                                        f"{second_name} sees one")
    if second.decision == Verdict.EMPTY:
        return Decision(Verdict.REJECT, f"not judged: the {second_name} sees no part ({second.reason}), the first "
                                        "camera sees one")
    return Decision(Verdict.PASS)
