"""Screen: a frame-only top-face AoLP statistic (validation sets only; no held-out set is read).

Physics: the AoLP of a specular reflection is set by the surface normal and the view ray, not by the light. A
horizontal face (the part's top face, the belt) shows one smooth AoLP field across the frame; a dent's or a
scratch's tilt out of the plane of incidence turns it. Per frame, at the sensor's resolution (the band rows
120-359, columns 80-559): Stokes from the raw mosaic (bilinear, as the station), blurred 1 px; the polarization's
direction 2a fitted as a plane over the most polarized half of the pixels; q = (S1 + i S2) e^(-2i a_fit), so
Im q = DoLP S0 sin 2(a - a_fit) in full-scale units; Im q / sqrt(S0) (shot noise) over the pixels polarized within
30 deg of the fit (``mask``), Gaussian-averaged (normalised convolution) at each of ``SIGMAS`` px, in units of its
robust spread over this frame; the score is its largest magnitude.

    python top_prior.py data/line-pf-train            # top_prior.npy, only for PRIOR >= 0
    PRIOR=-1 EDGE=0 python aolp_screen.py data/line-pv-val val303-A.json      # version A (no region prior)
    GT=1 PRIOR=-1 EDGE=0 python aolp_screen.py data/line-pv-val val303-gt.json  # the renderer's Stokes
    PRIOR=0.5 EDGE=0 python aolp_screen.py ...                                  # within the top-face prior
    PRIOR=0.5 EDGE=0.05 python aolp_screen.py ...                               # and away from intensity edges
"""
import json
import os
import sys
from concurrent.futures import ProcessPoolExecutor

import cv2
import numpy as np
from PIL import Image

from model.priors.demosaic import mosaic_to_stokes
from model.priors.mosaic import normalize_mosaic

HERE = os.path.dirname(os.path.abspath(__file__))
BAND = (slice(120, 360), slice(80, 560))
SIGMAS = (1.5, 3.0, 5.0)
PRIOR_MIN = float(os.environ.get("PRIOR", "-1"))
EDGE = float(os.environ.get("EDGE", "0"))


def gblur(x: np.ndarray, sigma: float) -> np.ndarray:
    return cv2.GaussianBlur(x, (0, 0), sigma, borderType=cv2.BORDER_REFLECT)


def top_prior() -> np.ndarray:
    if PRIOR_MIN < 0:
        return np.ones((BAND[0].stop - BAND[0].start, BAND[1].stop - BAND[1].start), np.float32)
    return np.load(os.path.join(HERE, "top_prior.npy"))[BAND]


def stokes_of(sample: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The band's (S0, S1, S2), blurred 1 px: from the raw mosaic, or the renderer's with GT=1."""
    if os.environ.get("GT"):
        g = np.load(f"{sample}/gt.npz")
        s = (g["s0"], g["s1"], g["s2"])
    else:
        s = mosaic_to_stokes(normalize_mosaic(np.array(Image.open(f"{sample}/raw.png")), 12).data)
    return tuple(gblur(np.ascontiguousarray(c[BAND]).astype(np.float32), 1.0) for c in s)


def im_map(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray, prior: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(Im q / sqrt(S0), mask as float): the polarization turned away from the frame's fitted plane in 2a."""
    h, w = s0.shape
    yy, xx = np.mgrid[0:h, 0:w].astype(np.float32)
    yy, xx = (yy - h / 2) / h, (xx - w / 2) / w
    p, two_a = np.hypot(s1, s2), np.arctan2(s2, s1)
    pmin = np.quantile(p, 0.5)
    sel = (p > pmin) & (prior > PRIOR_MIN)
    fit = np.full_like(s0, np.angle(np.sum(p[sel] * np.exp(1j * two_a[sel]))))
    for _ in range(3):
        d = np.angle(np.exp(1j * (two_a - fit)))
        use = sel & (np.abs(d) < np.radians(60))
        design = np.stack([np.ones(use.sum()), xx[use], yy[use]], 1)
        coef, *_ = np.linalg.lstsq(design * p[use, None], (d[use] + fit[use]) * p[use], rcond=None)
        fit = (coef[0] + coef[1] * xx + coef[2] * yy).astype(np.float32)
    q = (s1 + 1j * s2) * np.exp(-1j * fit)
    mask = (q.real > 0.5 * p) & sel
    if EDGE:
        ls = np.log(np.maximum(s0, 1e-3))
        grad = np.hypot(cv2.Sobel(ls, cv2.CV_32F, 1, 0), cv2.Sobel(ls, cv2.CV_32F, 0, 1)) / 8
        mask &= ~cv2.dilate((grad > EDGE).astype(np.uint8), np.ones((5, 5), np.uint8)).astype(bool)
    mask = cv2.erode(mask.astype(np.uint8), np.ones((5, 5), np.uint8)).astype(np.float32)
    return (q.imag / np.sqrt(np.maximum(s0, 1e-4))).astype(np.float32), mask


def zmaps(sample: str) -> dict[float, tuple[float, np.ndarray | None]]:
    """Per sigma: (score, the z map in the frame's robust units or None when too little is judged)."""
    im, mask = im_map(*stokes_of(sample), top_prior())
    out: dict[float, tuple[float, np.ndarray | None]] = {}
    for s in SIGMAS:
        gm = gblur(mask, s)
        zs = gblur(im * mask, s) / np.maximum(gm, 1e-6)
        valid = gm > 0.8
        if valid.sum() < 100:
            out[s] = (0.0, None)
            continue
        med = np.median(zs[valid])
        mad = 1.4826 * np.median(np.abs(zs[valid] - med)) + 1e-9
        z = np.where(valid, (zs - med) / mad, 0)
        out[s] = (float(np.abs(z).max()), z)
    return out


def sample_meta(root: str, name: str) -> dict:
    """Split, label, type and face of a rendered sample: top when the defect lies on the horizontal top face (its
    recorded surface normal within 25 deg of up; a scratch by its start on the top face, 9.6 mm above the belt)."""
    p = json.load(open(f"{root}/samples/{name}/params.json"))
    d = p.get("defect") or {}
    z = d["normal"][2] if "normal" in d else (1.0 if d.get("start_m", [0, 0, 0])[2] >= 0.0095 else 0.0)
    return {"name": name, "split": p["split"], "label": p["label"], "type": d.get("type", "good"),
            "face": "top" if z > 0.9 else "other", "px": d.get("visible_px", 0)}


def score(sample: str) -> dict[str, float]:
    return {f"s{s}": v[0] for s, v in zmaps(sample).items()}


def main(root: str, dest: str) -> None:
    names = sorted(os.listdir(f"{root}/samples"))
    with ProcessPoolExecutor(2) as ex:
        scores = ex.map(score, [f"{root}/samples/{n}" for n in names], chunksize=8)
        rows = [{**sample_meta(root, n), **s} for n, s in zip(names, scores, strict=True)]
    json.dump(rows, open(dest, "w"))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
