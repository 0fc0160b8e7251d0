"""A lens's smooth field, which the variation model can take out of every frame's residual (``smooth_field``).

A lens's vignetting (cos^4 of the field angle, and the lens's own fall of light toward its rim) multiplies the
intensity by a smooth field; in the variation model's intensity feature (log I less its median) it is added. Over the
few degrees of field the part spans it is close to a quadratic in the view's coordinates, which a dent, a scratch, a
stain or a missing stud, each local, barely projects on (docs/results/2026-12-09-smooth-field/plan.md)."""

from __future__ import annotations

import numpy as np

TERMS = ("x", "y", "x^2", "xy", "y^2")
"""The quadratic's non-constant terms, x and y the view's column and row scaled to [-1, 1]. The constant is left
out: the features' median already takes a frame's exposure out, and a part's offset against the belt is its own."""


def smooth_basis(region: np.ndarray, channels: int, intensity: int) -> np.ndarray:
    """(H, W) bool part region -> (len(TERMS), channels, H, W) float32: the ``TERMS`` on the ``intensity`` channel,
    each centred over the region and the set orthonormalised there (QR, float64), zero off the region and on every
    other channel. A term that the region cannot tell from the others (a region of one row or column) is zero.
    Projected out of a residual (``r - B^T (B r)`` on the flattened maps) it removes any quadratic field over the
    region and nothing else that is orthogonal to one."""
    h, w = region.shape
    out = np.zeros((len(TERMS), channels, h, w), np.float32)
    if region.sum() <= len(TERMS):
        return out
    yy, xx = np.mgrid[0:h, 0:w].astype(np.float64)
    x, y = 2 * xx / max(w - 1, 1) - 1, 2 * yy / max(h - 1, 1) - 1
    terms = np.stack([x, y, x * x, x * y, y * y])[:, region]  # (5, P)
    terms -= terms.mean(1, keepdims=True)
    q, r = np.linalg.qr(terms.T)  # (P, 5), (5, 5)
    keep = np.abs(np.diag(r)) > 1e-9 * np.abs(r).max()
    basis = np.zeros((len(TERMS), region.sum()))
    basis[keep] = q.T[keep]
    out[:, intensity][:, region] = basis
    return out
