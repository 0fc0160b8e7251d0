"""Check 64b, continued: how the stray light's change of a good part sits in the shipped variation model's features.

For each of seed 1168's good parts, the change the stray light makes (set A minus its twin B, the same part without
the spot) in the model's centred, scaled features ``u`` (registered, polarization and contrast aligned, as
``VariationModel._judged_residual`` makes them before the appearance projection). Reported: the share of that change
the model's 10 appearance components take out, and how few directions a basis learned from such twins needs to take
it out on other parts (fitted on the even-indexed parts, measured on the odd ones). The twins differ in their render
noise too (the spot changes the renderer's samples), so each is also measured after a Gaussian of ``SMOOTH_PX`` on
the change: the scale of the curvature window (3 px), where the change is the light's, not the noise's.

Usage (repository root): python docs/results/2026-11-30-report-1167/stray64d.py data/twins-1168-A data/twins-1168-B
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import cv2
import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL = "model/weights/default"
SMOOTH_PX = 2.0


def features(var, xi: np.ndarray) -> np.ndarray:
    """(C, H, W) physical priors -> ``u`` (C, H, W), as ``_judged_residual`` makes it before the projection."""
    mean, part = var.mean.numpy(), var.region.numpy()
    warped, _, where = var._aligned(xi)
    warped[:-1], _ = var.align_contrast(warped[:-1], where)
    return (warped[:-1] - mean) / var.channel_scale.numpy()[:, None, None] * part


def share_taken(basis: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Per row of ``d`` (N, D): the share of its energy in the span of ``basis``'s orthonormal rows (K, D)."""
    return ((d @ basis.T) ** 2).sum(1) / np.maximum((d ** 2).sum(1), 1e-12)


def main() -> None:
    a_dir, b_dir = sys.argv[1:3]
    ck = load_checkpoint(MODEL)
    var = ck.detector.variation
    sa, sb = (model_split(ck, MODEL, d, "test", good_only=True) for d in (a_dir, b_dir))
    assert list(sa.index) == list(sb.index)
    stray = np.array([json.loads((Path(a_dir) / "samples" / f"{i:06d}" / "params.json").read_text())
                      ["scene"]["light"]["intensity"] for i in sa.index])
    raw = np.stack([features(var, xa) - features(var, xb) for xa, xb in
                    zip(sa.priors.float().numpy(), sb.priors.float().numpy(), strict=True)])
    part = var.region.numpy()
    smooth = np.stack([[cv2.GaussianBlur(c, (0, 0), SMOOTH_PX) * part for c in di] for di in raw])
    lit = stray > 0.05
    for name, d in (("as rendered", raw), (f"smoothed by {SMOOTH_PX:g} px", smooth)):
        print(f"## The change {name}\n")
        report(var, d.reshape(len(d), -1), lit)


def report(var, d: np.ndarray, lit: np.ndarray) -> None:
    """Print the shares for the (N, D) changes ``d`` of the parts ``lit``."""
    p = var.components.numpy().reshape(len(var.components), -1)
    p = p[np.linalg.norm(p, axis=1) > 0]
    taken = share_taken(p, d[lit])
    print(f"{int(lit.sum())} of {len(d)} good parts with a stray light above 0.05 (their change is measured).\n")
    print(f"The model's {len(p)} appearance components take out a median {np.median(taken):.0%} of the stray light's "
          f"change (quartiles {np.percentile(taken, 25):.0%}-{np.percentile(taken, 75):.0%}).\n")
    idx = np.flatnonzero(lit)
    fit, test = idx[::2], idx[1::2]
    vt = np.linalg.svd(d[fit], full_matrices=False)[2]
    print("| basis | directions | share of the change taken out on the other parts: median | quartiles |")
    print("|---|---|---|---|")
    for k in (1, 3, 5, 10, 20, 40):
        both = np.linalg.qr(np.concatenate([p, vt[:k]]).T)[0].T
        for name, b in ((f"twins' first {k}", vt[:k]), (f"model's components + twins' first {k}", both)):
            s = share_taken(b, d[test])
            print(f"| {name} | {len(b)} | {np.median(s):.0%} | {np.percentile(s, 25):.0%}-{np.percentile(s, 75):.0%} |")


if __name__ == "__main__":
    main()
