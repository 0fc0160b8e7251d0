"""Stop 67 screen: the curvature window where its support runs off the judged pixels.

The shipped window (``model.draem.variation.VariationModel.window``) filters each channel's signed z with zeros
outside the judged pixels: off the part, and where the highlight rule hides a place. A good part whose residual
is not zero next to such an edge then answers as a step, and where the highlight's edge moves from part to part the
per-place calibration cannot take that out. Statistics, each the largest channel's |sigma^2 LoG_3| of:
  log3        z with zeros outside the judged pixels (the shipped window);
  fillS       z with the pixels outside the judged ones filled by the judged pixels' Gaussian-weighted mean over
              S px (normalised convolution), zero where under 5 % of that weight is judged: a step at an edge
              of the judged pixels becomes a smooth continuation, a defect's own signal stays;
  fillS_in    the same, filled only inside the part region (the silhouette keeps its zeros; only hidden highlights
              are filled).
Scored as the ridge screen (window_screen.py of 2026-11-29-ridge). Usage: python screen.py MODEL VAL OUT.json"""
import sys

import cv2
import numpy as np
from window_screen import screen

from model.draem.checkpoint import load_checkpoint
from model.draem.variation import curvature

FILLS = (2.0, 4.0, 8.0)
MIN_WEIGHT = 0.05


def filled(z: np.ndarray, judged: np.ndarray, s: float, where: np.ndarray | None = None) -> np.ndarray:
    """(C, H, W) z (zero outside ``judged``) -> z with the unjudged pixels (within ``where``, default all) set to the
    judged pixels' Gaussian-weighted mean over ``s`` px."""
    m = judged.astype(np.float32)
    w = cv2.GaussianBlur(m, (0, 0), s, borderType=cv2.BORDER_REPLICATE)
    fill_at = ~judged & (w > MIN_WEIGHT) & (np.ones_like(judged) if where is None else where)
    out = z.copy()
    for c, zc in enumerate(z):
        num = cv2.GaussianBlur(zc * m, (0, 0), s, borderType=cv2.BORDER_REPLICATE)
        out[c][fill_at] = (num / np.maximum(w, MIN_WEIGHT))[fill_at]
    return out


REGION = load_checkpoint(sys.argv[1]).detector.variation.region.numpy()  # the part region, as zmaps has it


def stats(z, judged):
    o = {"log3": np.max([curvature(zc, 3.0) for zc in z], 0)}
    for s in FILLS:
        o[f"fill{s:g}"] = np.max([curvature(zc, 3.0) for zc in filled(z, judged, s)], 0)
        o[f"fill{s:g}_in"] = np.max([curvature(zc, 3.0) for zc in filled(z, judged, s, REGION)], 0)
    return o


screen(stats, lambda names: [(k,) for k in names])
