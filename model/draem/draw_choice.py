"""Which of several trainings (draws) of one recipe to keep: the one that rejects fewest good parts of a set.

Trainings of one recipe that differ only in their seed agree on the line as built and can disagree on frames the
training never showed: the shipped recipe's look network, trained four times, rejected 3-5 of 175 good parts as built
and 4 to 51 through a lens (docs/results/2026-12-10-look-lens.md, addendum). The rule below keeps, of such draws,
the one that rejects fewest good parts of a set (the validation parts seen through a lens, not a test set), each
draw at its own stored threshold; a tie goes to the draw catching more of the set's defective parts, a tie of both
to the first named. A part is rejected when its score is above the threshold or is not a number (the station's
fail-closed rule: a part it cannot score is rejected).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

RULE = "fewest good parts rejected at its own threshold; then most defective caught; then the first named"


@dataclass(frozen=True)
class DrawCounts:
    """One draw on one set: its name and threshold, and its good and defective parts, all and rejected."""

    name: str
    threshold: float
    good: int
    good_rejected: int
    defective: int
    caught: int

    def line(self) -> str:
        caught = f"{self.caught} of {self.defective} defective caught" if self.defective else "no defective parts"
        return (f"{self.name}: {self.good_rejected} of {self.good} good rejected, {caught} "
                f"(threshold {self.threshold:.6g})")


@dataclass(frozen=True)
class DrawChoice:
    """The draws' counts in the order named, and the index of the one kept (``RULE``)."""

    counts: tuple[DrawCounts, ...]
    kept: int

    @property
    def kept_name(self) -> str:
        return self.counts[self.kept].name


def draw_counts(name: str, threshold: float, labels: np.ndarray, scores: np.ndarray) -> DrawCounts:
    """Counts of draw ``name`` at ``threshold`` on a set: ``labels`` 0 good / 1 defective, ``scores`` the draw's
    image scores (rejected above the threshold, or not a number)."""
    labels, scores = np.asarray(labels), np.asarray(scores, dtype=np.float64)
    if labels.shape != scores.shape:
        raise ValueError(f"{name}: {labels.shape[0]} labels against {scores.shape[0]} scores")
    rejected = ~(scores <= threshold)  # NaN is rejected
    good = labels == 0
    return DrawCounts(name, float(threshold), int(good.sum()), int(rejected[good].sum()), int((~good).sum()),
                      int(rejected[~good].sum()))


def choose_draw(counts: Sequence[DrawCounts]) -> DrawChoice:
    """The draw ``RULE`` keeps of ``counts`` (at least two, each on the same set's good parts)."""
    if len(counts) < 2:
        raise ValueError(f"a choice needs at least two draws, got {len(counts)}")
    if len({c.good for c in counts}) != 1:
        raise ValueError("the draws were counted on different numbers of good parts: " +
                         ", ".join(f"{c.name} {c.good}" for c in counts))
    if counts[0].good == 0:
        raise ValueError("the set has no good parts: the rule counts good parts rejected")
    kept = min(range(len(counts)), key=lambda i: (counts[i].good_rejected, -counts[i].caught, i))
    return DrawChoice(tuple(counts), kept)
