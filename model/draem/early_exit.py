"""Early exit of the per-prior ensemble: stop running members once the part's decision is settled.

The ensemble's image score is the mean of its M members' scores, each in [0, 1], and a part is rejected when the
score exceeds the threshold. After the first k members (scores summing to ``s``):

exact (``margin`` 0)  the members not run yet can move the mean only within [s / M, (s + M - k) / M]; when that
                      interval lies wholly on one side of the threshold, the decision cannot change. No accuracy
                      cost, but it rarely fires for good parts (the rest could still all score 1).
margin m > 0          also stop when the running mean ``s / k`` is more than ``m`` from the threshold, betting that
                      the other members agree with the first ones. Approximate: ``simulate`` measures the cost.

The score reported after an exit is the running mean ``s / k``; with the exact rule it is on the same side of the
threshold as the full mean (``s / k`` lies within the interval above). Numpy only.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np


def decided(partial: Sequence[float], n_members: int, threshold: float, margin: float = 0.0) -> bool:
    """Whether the decision is settled after the members whose scores are ``partial`` (in run order)."""
    k = len(partial)
    if k == 0:
        return False
    if k >= n_members:
        return True
    s = float(sum(partial))
    if s / n_members > threshold or (s + n_members - k) / n_members <= threshold:
        return True
    return margin > 0 and abs(s / k - threshold) > margin


def simulate(member_scores: np.ndarray, threshold: float, margin: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Replay early exit on known member scores (N, M), members in run order: (score (N,), members run (N,))."""
    scores = np.asarray(member_scores, dtype=np.float64)
    n, m = scores.shape
    out, used = np.empty(n), np.empty(n, dtype=np.int64)
    for i in range(n):
        k = next(k for k in range(1, m + 1) if decided(scores[i, :k], m, threshold, margin))
        out[i], used[i] = scores[i, :k].mean(), k
    return out, used
