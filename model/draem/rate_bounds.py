"""How far a share counted on a finite set of parts can be trusted: exact binomial bounds.

Convention: ``k`` of ``n`` parts (good parts rejected, or defective parts caught), 0 <= k <= n, n >= 1; rates are
fractions in [0, 1]; ``confidence`` in (0, 1).

- ``upper_bound(k, n, confidence)``: the one-sided Clopper-Pearson bound, the largest true rate under which seeing
  k or fewer of n is still at least 1 - ``confidence`` likely. It is also, exactly, the ``confidence`` quantile of the
  share of *new* good parts above a threshold that k of n good validation parts lie above (scores of good parts
  exchangeable, no ties; ``metrics.choose_threshold``'s threshold is such a one): that share follows
  Beta(k + 1, n - k), whatever the scores' distribution. Its mean is ``expected_rate`` = (k + 1) / (n + 1).
- ``interval(k, n, confidence)``: the two-sided Clopper-Pearson interval, for a share measured on a held-out set.
- ``either_rate(ks, n, confidence)``: the same for a part rejected when it lies above any of several thresholds
  set on the same n good parts (two cameras' split), ks[i] above threshold i: the sums, which err high.
- ``allowed_above(n, rate, confidence)``: the most of n good parts a threshold may leave above it and keep that
  promise (``metrics.choose_threshold(..., confidence=)``).
- ``parts_needed(rate, confidence, k)``: the fewest good validation parts with which a threshold that k of them lie
  above has ``upper_bound`` at or below ``rate``.

Why it matters: the station's rule (at most 1 % of the good validation parts rejected) on 370 good parts lets 3 lie
above the threshold. New good parts are then rejected at about 1.1 % on average, and at up to 2.1 % on one line
in twenty: what the held-out seeds of docs/results showed (0-2.3 % for the line camera, 1.18 % over seven sets;
1.9-3.4 % for two cameras, whose shares add: docs/results/2026-11-30-threshold-counts.md). To hold 1 % with 95 %
confidence a threshold needs 299 good parts and none above it, or 773 with 3 above it (``parts_needed``;
docs/model.md, "What a count of good parts can promise").
"""

from __future__ import annotations

from collections.abc import Sequence

from scipy.stats import beta


def _check(k: int, n: int, confidence: float) -> None:
    if not (n >= 1 and 0 <= k <= n):
        raise ValueError(f"a share needs 0 <= k <= n and n >= 1, got k={k}, n={n}")
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must be in (0, 1), got {confidence}")


def expected_rate(k: int, n: int) -> float:
    """The mean share of new good parts above a threshold that ``k`` of ``n`` good validation parts lie above."""
    _check(k, n, 0.5)
    return (k + 1) / (n + 1)


def upper_bound(k: int, n: int, confidence: float = 0.95) -> float:
    """One-sided Clopper-Pearson upper bound on the rate behind ``k`` of ``n`` (module docstring); 1.0 when k = n."""
    _check(k, n, confidence)
    return 1.0 if k == n else float(beta.ppf(confidence, k + 1, n - k))


def interval(k: int, n: int, confidence: float = 0.95) -> tuple[float, float]:
    """Two-sided Clopper-Pearson interval (low, high) on the rate behind ``k`` of ``n``."""
    _check(k, n, confidence)
    a = (1.0 - confidence) / 2.0
    low = 0.0 if k == 0 else float(beta.ppf(a, k, n - k + 1))
    high = 1.0 if k == n else float(beta.ppf(1.0 - a, k + 1, n - k))
    return low, high


def either_rate(ks: Sequence[int], n: int, confidence: float = 0.95) -> tuple[float, float]:
    """Several thresholds on the same ``n`` good parts (one per camera), ``ks[i]`` of them above threshold i; a new
    good part is rejected when it lies above any -> (at most the expected share rejected: the sum of each one's
    ``expected_rate``; the share's bound at ``confidence``: the sum of each one's ``upper_bound`` at 1 - (1 -
    ``confidence``) / len(ks), Bonferroni). Both ignore the parts above two at once, so they err high."""
    if not ks:
        raise ValueError("either_rate needs at least one threshold's count")
    _check(0, n, confidence)
    each = 1.0 - (1.0 - confidence) / len(ks)
    return (min(1.0, sum(expected_rate(k, n) for k in ks)),
            min(1.0, sum(upper_bound(k, n, each) for k in ks)))


def allowed_above(n: int, rate: float, confidence: float = 0.95) -> int:
    """The most of ``n`` good validation parts a threshold may leave above it while its ``upper_bound`` stays at or
    under ``rate`` (``metrics.choose_threshold``'s promise); ValueError, naming ``parts_needed``, when not even none
    may."""
    if not upper_bound(0, n, confidence) <= rate:
        raise ValueError(f"{n} good parts cannot promise at most {rate:.2%} of new good parts rejected at "
                         f"{confidence:.0%} confidence: that needs {parts_needed(rate, confidence)} or more")
    k = 0
    while k + 1 < n and upper_bound(k + 1, n, confidence) <= rate:
        k += 1
    return k


def parts_needed(rate: float, confidence: float = 0.95, k: int = 0) -> int:
    """The fewest good parts n with ``upper_bound(k, n, confidence) <= rate`` (a threshold ``k`` of them lie above)."""
    if not 0.0 < rate < 1.0:
        raise ValueError(f"rate must be in (0, 1), got {rate}")
    _check(0, 1, confidence)
    if k < 0:
        raise ValueError(f"k must be >= 0, got {k}")
    lo, hi = k + 1, k + 2
    while upper_bound(k, hi, confidence) > rate:  # the bound falls as n grows: bracket, then bisect
        lo, hi = hi, 2 * hi
    while lo < hi:
        mid = (lo + hi) // 2
        lo, hi = (lo, mid) if upper_bound(k, mid, confidence) <= rate else (mid + 1, hi)
    return lo
