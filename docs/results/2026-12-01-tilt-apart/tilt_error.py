"""How fine a tilt measurement the two dome halves give (the page's reading, after the screen): on the first good
parts of T's validation twins, the tilt prior `tilt_x` against the renderer's normal's x component (camera frame,
x right), over the part's pixels, at the priors' resolution (the mosaic's: half the frame's; the normals are
averaged over 2 x 2) and smoothed with a Gaussian of 10 frame px (degrade.py's scale in
2026-12-01-normal-precision). One line t = k n_x + c is fitted over all parts' pixels at each scale (a region
of the part, the body more than 2 mm from the studs and the outline or the rest, is read with its scale's line); the
error of the
measurement is (t - k n_x - c) / k, read as degrees of tilt along x. With --unpolarized the tilt is taken from each
frame's unpolarized intensity S0 - sqrt(S1^2 + S2^2) instead of S0 (a check written after the screen: a glossy
face's mirror image of the dome is partly polarized, its diffuse light barely). For comparison, the degraded
normals' error along x alone: its median is 0.57 times their median angular error (two independent Gaussian components).

Usage: PYTHONPATH=. python tilt_error.py [PARTS] [--unpolarized] (default 40; reads data/tilt-pv-val)"""
import sys

import numpy as np
from scipy.ndimage import distance_transform_edt, gaussian_filter

from model.priors.api import compute_set_priors, set_stokes
from sim.dataset import open_dataset

ds = open_dataset("data/tilt-pv-val")
args = [a for a in sys.argv[1:] if a != "--unpolarized"]
unpolarized = "--unpolarized" in sys.argv
want = int(args[0]) if args else 40
keys = ("pixel", "10 px", "10 px, body far from studs", "10 px, near studs or outline")
ts, ns, parts = {k: [] for k in keys}, {k: [] for k in keys}, 0
for i in ds.indices("val"):
    s = ds.load(i)
    if s.label:
        continue
    if unpolarized:
        _, (a, b) = set_stokes(s.raws, ds.manifest["layout"], "bilinear", True, ds.manifest["bit_depth"])
        u0, u1 = (np.maximum(st[0] - np.hypot(st[1], st[2]), 0.0).astype(np.float64) for st in (a, b))
        t = np.where(u0 + u1 > 1e-6, (u0 - u1) / np.maximum(u0 + u1, 1e-6), 0.0)
    else:
        t = compute_set_priors(s.raws, ds.dome_segments, ds.manifest["layout"], priors=["tilt_x"],
                               bit_depth=ds.manifest["bit_depth"])["tilt_x"].astype(np.float64)
    h, w_ = t.shape
    f = s.normal.shape[0] // h
    nx = s.normal[:h * f, :w_ * f, 0].reshape(h, f, w_, f).mean(axis=(1, 3)).astype(np.float64)
    mask = s.object_mask[:h * f, :w_ * f].reshape(h, f, w_, f).all(axis=(1, 3))
    sigma = 10.0 / f
    w = gaussian_filter(mask.astype(np.float64), sigma)
    inner = mask & (w > 0.9)  # away from the part's outline, where smoothing mixes in the belt
    # the body (part 1) more than 20 frame px (about 2 mm) from any other part (the studs, the plug) and the outline
    body = s.part_index[:h * f, :w_ * f].reshape(h, f, w_, f).min(axis=(1, 3)) == 1
    far = body & (distance_transform_edt(body) * f > 20.0)
    smooth = (gaussian_filter(t * mask, sigma) / np.maximum(w, 1e-9),
              gaussian_filter(nx * mask, sigma) / np.maximum(w, 1e-9))
    for name, (a, b), where in (("pixel", (t, nx), inner), ("10 px", smooth, inner),
                                ("10 px, body far from studs", smooth, inner & far),
                                ("10 px, near studs or outline", smooth, inner & ~far)):
        ts[name].append(a[where])
        ns[name].append(b[where])
    parts += 1
    if parts == want:
        break
fits = {}
for name in ts:  # the regions are read with the line of all the part's pixels at their scale
    t, nx = np.concatenate(ts[name]), np.concatenate(ns[name])
    k, c = fits.setdefault(name.split(",")[0], tuple(np.polyfit(nx, t, 1)))
    err = np.degrees(np.abs(t - k * nx - c) / abs(k))
    head = f"{'unpolarized, ' if unpolarized else ''}{name}"
    print(f"{head}: {parts} good parts, {t.size} pixels; t = {k:.3f} n_x + {c:+.3f}; error along x: median "
          f"{np.median(err):.2f} deg, 90th percentile {np.percentile(err, 90):.2f} deg")
