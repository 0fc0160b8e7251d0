"""Clusters of good parts by appearance: the variation model's local appearance (``VariationModel``'s ``clusters``).

The variation model takes the line's shared changes out with a few global principal components: a linear model.
The part's yaw, the light's position and the finish change a frame non-linearly (a highlight that moves, a mirror
image that turns), and one residual scale per pixel serves every kind of good part. Grouping the good parts by their
components' coefficients (k-means) and judging a part against the groups near it (their mean residual taken out,
their residual scale put in) takes out what the components leave of that. Pure numpy.

Convention: coefficients are the parts' least-squares coefficients on the fit's components (``VariationModel``'s
``_residual``), compared in units of ``spread``: per component, their standard deviation over the good parts
(floored) times the good parts' median distance to their nearest centre in those units, so that a typical good part
lies 1 from its centre. A part is judged against every cluster, weighted by exp(-d^2 / 2) of its distance d to the
cluster's centre (normalised; ``weights``): a hard choice of the nearest cluster made the validation AUROC depend on
the k-means seed (0.898-0.910 over 4 seeds), the weighted one did not (0.905-0.906;
docs/results/2026-11-28-appearance-clusters/screen/screen.md). Residuals are in units of the fit's per-pixel
``scale`` (z), over the part region's pixels only (C, P), as the model file keeps them; the weighted mean is
sum w_k m_k and the weighted scale sqrt(sum w_k s_k^2) (``blend``).
"""

from __future__ import annotations

import numpy as np

CLUSTER_PARTS = 40
"""A fit keeps at most one cluster per this many good parts (376 parts: up to 9); fewer than 2 clusters: none."""

MIN_CLUSTER_PARTS = 10
"""Smallest cluster kept: a smaller one's parts go to the nearest other cluster (a scale from a handful of parts is
noise)."""

SCALE_FLOOR = 0.3
"""Smallest cluster scale, in units of the fit's per-pixel scale: where a cluster's few parts happen to agree, a part
is not judged on differences the line as a whole does not resolve."""

RESTARTS = 10
"""k-means starts (k-means++ seeding, seed 0); the one with the least within-cluster sum of squares is kept."""

SPREAD_FLOOR = 1e-6
"""Floor of a coefficient's spread (a component a small fit leaves unused has coefficients 0)."""


def spread_of(coefs: np.ndarray) -> np.ndarray:
    """(N, K) coefficients -> (K,) their standard deviation over the parts, floored at ``SPREAD_FLOOR``."""
    return np.maximum(coefs.std(0), SPREAD_FLOOR).astype(np.float32)


def sq_distances(points: np.ndarray, centres: np.ndarray) -> np.ndarray:
    """(N, K) points and (M, K) centres -> (N, M) squared Euclidean distances."""
    return ((points[:, None] - centres[None]) ** 2).sum(2)


def kmeans(points: np.ndarray, k: int, restarts: int = RESTARTS, seed: int = 0, steps: int = 100
           ) -> tuple[np.ndarray, np.ndarray]:
    """(N, D) points -> ((k, D) centres, (N,) labels) by Lloyd's k-means from k-means++ seeds, the best of
    ``restarts``; deterministic for a seed. A centre left without points keeps its place."""
    rng = np.random.default_rng(seed)
    best: tuple[float, np.ndarray, np.ndarray] | None = None
    for _ in range(restarts):
        centres = points[[rng.integers(len(points))]]
        while len(centres) < k:
            d = sq_distances(points, centres).min(1)
            p = d / d.sum() if d.sum() > 0 else None
            centres = np.concatenate([centres, points[[rng.choice(len(points), p=p)]]])
        for _ in range(steps):
            labels = nearest(centres, points)
            moved = np.stack([points[labels == j].mean(0) if (labels == j).any() else centres[j] for j in range(k)])
            if np.allclose(moved, centres):
                break
            centres = moved
        labels = nearest(centres, points)
        inertia = float(((points - centres[labels]) ** 2).sum())
        if best is None or inertia < best[0]:
            best = (inertia, centres, labels)
    assert best is not None
    return best[1], best[2]


def group(coefs: np.ndarray, clusters: int) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """(N, K) good parts' coefficients -> ((M, K) centres in ``spread`` units, (K,) spread (module docstring),
    (N,) labels), M at most ``clusters`` and N // ``CLUSTER_PARTS``, every cluster at least ``MIN_CLUSTER_PARTS``
    parts (the smallest merged into the nearest others, one at a time); None when fewer than 2 clusters are left."""
    m = min(clusters, len(coefs) // CLUSTER_PARTS)
    if m < 2:
        return None
    spread = spread_of(coefs)
    points = coefs / spread
    centres, labels = kmeans(points, m)
    while len(centres) > 1:
        counts = np.bincount(labels, minlength=len(centres))
        if counts.min() >= MIN_CLUSTER_PARTS:
            break
        centres = np.delete(centres, counts.argmin(), 0)
        labels = nearest(centres, points)
        centres = np.stack([points[labels == j].mean(0) if (labels == j).any() else centres[j]
                            for j in range(len(centres))])
        labels = nearest(centres, points)
    if len(centres) < 2:
        return None
    width = max(float(np.median(np.sqrt(sq_distances(points, centres).min(1)))), SPREAD_FLOOR)
    return (centres / width).astype(np.float32), (spread * width).astype(np.float32), labels


def nearest(centres: np.ndarray, points: np.ndarray) -> np.ndarray:
    """(M, K) centres and (N, K) points, both in spread units -> (N,) index of each point's nearest centre."""
    return sq_distances(points, centres).argmin(1)


WEIGHT_FLOOR = 1e-4
"""Clusters weighing less than this (before normalising; the nearest weighs 1) are left out of a blend."""


def weights(centres: np.ndarray, point: np.ndarray) -> np.ndarray:
    """(M, K) centres and (K,) a part's coefficients, both in ``spread`` units -> (M,) weights exp(-d^2 / 2) relative
    to the nearest centre's, those under ``WEIGHT_FLOOR`` zero, normalised to sum 1; the nearest alone when the
    distances are not finite."""
    d2 = sq_distances(point[None], centres)[0]
    if not np.isfinite(d2).all():
        w = np.zeros(len(centres))
        w[int(np.nan_to_num(d2, nan=np.inf).argmin())] = 1.0
        return w
    w = np.exp(-(d2 - d2.min()) / 2.0)
    w[w < WEIGHT_FLOOR] = 0.0
    return w / w.sum()


def blend(w: np.ndarray, stats: list[tuple[np.ndarray, np.ndarray]]) -> tuple[np.ndarray, np.ndarray]:
    """(M,) weights and each cluster's (mean, scale) -> the weighted (mean, scale): sum w_k m_k and
    sqrt(sum w_k s_k^2), over the clusters with weight (float32)."""
    used = [(wk, m, s) for wk, (m, s) in zip(w, stats, strict=True) if wk > 0]
    mean = sum(wk * m for wk, m, _ in used)
    scale = np.sqrt(sum(wk * s.astype(np.float32) ** 2 for wk, _, s in used))
    return np.asarray(mean, np.float32), np.asarray(scale, np.float32)


def residual_stats(r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(n, C, P) residuals (z) of a cluster's parts -> ((C, P) mean, (C, P) scale: 1.4826 MAD about the mean, times
    sqrt(n / (n - 1)) for the mean's own fit, floored at ``SCALE_FLOOR``)."""
    n = len(r)
    mean = r.mean(0)
    mad = np.median(np.abs(r - mean), 0)
    return mean, np.maximum(1.4826 * mad * np.sqrt(n / max(n - 1, 1)), SCALE_FLOOR)
