"""Two cameras' files on the same parts, one decision: a part is rejected when either camera's score is above that
camera's threshold, and the budget of good parts rejected is split between the two on validation (check 68's rule,
docs/results/2026-11-30-wide-dome.md; read on fresh seeds in checks 69 and 70).

The rule: on validation parts seen by both cameras, for k = 0, 1, ..., budget (budget = floor(rate x good parts)),
the second camera's threshold leaves its k highest good scores above it (k = 0: its highest itself), and
the first camera's is the lowest that keeps the union within the budget. The k that catches the most defective
validation parts is kept (ties: the smaller k, which gives the first camera more of the budget).

``expected_budget``: the budget that holds the rate for *new* good parts on average rather than as a count on these
(``rate_bounds``: a threshold that k of n good parts lie above rejects about (k + 1) / (n + 1) of new ones, and two
cameras' shares add): floor(rate x (n + 1)) - 2, so 1 on 368 good twins at 1 % where the count allows 3.

Scores: higher is more anomalous; a camera rejects when ``score > threshold``, as the station does. Pure numpy.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class SplitThresholds:
    """One way to split the budget: the two thresholds and what they do on validation."""

    first: float
    """The first camera's threshold (the line camera's, in checks 68-70)."""
    second: float
    """The second camera's threshold."""
    k: int
    """The good validation parts the second camera rejects."""
    good_rejected: int
    """The good validation parts either camera rejects (at most the budget)."""
    caught: float
    """The share of defective validation parts either camera rejects."""


def _leaving_above(scores: np.ndarray, k: int) -> float:
    """A threshold with at most the ``k`` highest of ``scores`` above it (exactly k without ties; k = 0: the highest
    itself; k >= size: below all)."""
    s = np.sort(scores)[::-1]
    return float(s[k]) if k < s.size else float(s[-1]) - 1.0 if s.size else math.inf


def count_budget(n_good: int, rate: float) -> int:
    """The good validation parts, of ``n_good``, the thresholds together may leave above them when ``rate`` is held
    as a count on these: floor(rate x n_good) (module docstring; ``station split --budget count``)."""
    return math.floor(rate * n_good + 1e-9)


def expected_budget(n_good: int, rate: float, cameras: int = 2) -> int:
    """The most good validation parts, of ``n_good``, the ``cameras`` thresholds together may leave above them while
    new good parts are rejected at most at ``rate`` on average (module docstring); ValueError when not even none."""
    budget = math.floor(rate * (n_good + 1) + 1e-9) - cameras
    if budget < 0:
        need = math.ceil(cameras / rate - 1 - 1e-9)
        raise ValueError(f"{n_good} good parts cannot hold {rate:.2%} of new good parts rejected by {cameras} cameras "
                         f"on average: that needs {need} or more")
    return budget


def split_thresholds(defective: np.ndarray, first: np.ndarray, second: np.ndarray,
                     rate: float = 0.01, budget: int | None = None) -> tuple[list[SplitThresholds], int]:
    """Every split of the budget on validation, and the index of the chosen one (see the module).

    defective: (N,) bool; first, second: (N,) each camera's score of the same N parts; rate in [0, 1): the share of
    good parts the two cameras together may reject (``budget``, when given, is the count instead, as
    ``expected_budget`` makes it). Raises ValueError without good parts, on mismatched lengths or on a non-finite
    score."""
    y = np.asarray(defective, bool).reshape(-1)
    a, b = (np.asarray(x, np.float64).reshape(-1) for x in (first, second))
    if not (a.size == b.size == y.size):
        raise ValueError(f"split_thresholds: {y.size} labels, {a.size} and {b.size} scores")
    if not 0.0 <= rate < 1.0:
        raise ValueError(f"rate must be in [0, 1), got {rate}")
    if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
        raise ValueError("split_thresholds: scores contain NaN or Inf")
    good = ~y
    if not good.any():
        raise ValueError("no good parts: a rate of good parts rejected cannot be split")
    if budget is None:
        budget = count_budget(int(good.sum()), rate)
    elif budget < 0:
        raise ValueError(f"budget must be >= 0, got {budget}")
    rows = []
    for k in range(budget + 1):
        t_second = _leaving_above(b[good], k)
        by_second = b > t_second
        passed = np.sort(a[good & ~by_second])[::-1]  # good parts the second camera passes, highest first
        t_first = _leaving_above(passed, budget - int(by_second[good].sum()))
        rejected = by_second | (a > t_first)
        rows.append(SplitThresholds(t_first, t_second, k, int(rejected[good].sum()),
                                    float(rejected[y].mean()) if y.any() else math.nan))
    best = max(range(len(rows)), key=lambda i: (0.0 if math.isnan(rows[i].caught) else rows[i].caught, -i))
    return rows, best


def split_rejects(first: np.ndarray, second: np.ndarray, split: SplitThresholds) -> np.ndarray:
    """(N,) bool: the parts either camera rejects under ``split``."""
    return (np.asarray(first) > split.first) | (np.asarray(second) > split.second)
