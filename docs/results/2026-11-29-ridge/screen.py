"""Stop 60 screen: line (ridge) responses of the signed residual beside the shipped curvature window.

A scratch is a line 0.5-1 mm wide and 4-15 mm long (sim/defects.py): the Laplacian at sigma 3 (the shipped window)
answers blobs. Statistics, each the largest channel's absolute response to its signed z:
  log3        sigma^2 LoG_3, the shipped window (``model.draem.variation.curvature``);
  hessS       the scale-normalised Hessian's largest |eigenvalue| at sigma S (isotropic: a line or a blob);
  lineSxL     an oriented line filter: sigma^2 times the second derivative across of a Gaussian of sigma S across and
              L along, 8 angles, the largest |response| (integrates a line's signed contrast along its length).
Calibration and scoring: window_screen.py (its code was this file's until the dent screen shared it; the outputs are
the same). Usage: python screen.py MODEL VAL OUT.json [HELDOUT...]"""
import cv2
import numpy as np
from window_screen import screen

from model.draem.variation import curvature

ANGLES = 8


def line_kernels(s: float, length: float) -> list[np.ndarray]:
    r = int(np.ceil(4 * max(s, length)))
    y, x = np.mgrid[-r:r + 1, -r:r + 1].astype(np.float64)
    ks = []
    for a in np.arange(ANGLES) * np.pi / ANGLES:
        u = x * np.cos(a) + y * np.sin(a)  # across
        v = -x * np.sin(a) + y * np.cos(a)  # along
        g = np.exp(-0.5 * (u / s) ** 2 - 0.5 * (v / length) ** 2)
        g /= g.sum()
        k = (u * u / s**2 - 1.0) * g
        ks.append((k - k.mean()).astype(np.float32))  # zero sum: a flat field gives 0
    return ks


def hessian_max(z: np.ndarray, s: float) -> np.ndarray:
    b = cv2.GaussianBlur(z, (0, 0), s, borderType=cv2.BORDER_REPLICATE)
    dxx = cv2.Sobel(b, cv2.CV_32F, 2, 0, ksize=3)
    dyy = cv2.Sobel(b, cv2.CV_32F, 0, 2, ksize=3)
    dxy = cv2.Sobel(b, cv2.CV_32F, 1, 1, ksize=3) / 4.0
    half = np.sqrt(((dxx - dyy) / 2) ** 2 + dxy**2)
    m = (dxx + dyy) / 2
    return s * s * np.maximum(np.abs(m + half), np.abs(m - half))


LINES = {f"line{s}x{L}": line_kernels(s, L) for s in (1.0, 1.5) for L in (3.0, 5.0)}
HESS = (1.0, 1.5, 2.0)


def stats(z, judged):
    o = {"log3": np.max([curvature(zc, 3.0) for zc in z], 0)}
    for s in HESS:
        o[f"hess{s}"] = np.max([hessian_max(zc, s) for zc in z], 0)
    for name, ks in LINES.items():
        o[name] = np.max([np.abs(cv2.filter2D(zc, cv2.CV_32F, k, borderType=cv2.BORDER_REPLICATE))
                          for zc in z for k in ks], 0)
    return o


screen(stats, lambda names: [(k,) for k in names] + [("log3", k) for k in names if k != "log3"])
