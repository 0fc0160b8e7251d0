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

Usage: PYTHONPATH=. python tilt_error.py [PARTS] [--unpolarized] [--data SET] (default 40 parts of
data/tilt-pv-val; nostray.toml's check reads data/tilt-pv-val-nostray, the same parts with the stray lamp off)"""
import sys

import numpy as np
from scipy.ndimage import distance_transform_edt, gaussian_filter

from model.priors.api import compute_set_priors, set_stokes
from sim.dataset import open_dataset

argv = sys.argv[1:]
root = argv.pop(argv.index("--data") + 1) if "--data" in argv else "data/tilt-pv-val"
ds = open_dataset(root)
args = [a for a in argv if a not in ("--unpolarized", "--data")]
unpolarized = "--unpolarized" in argv
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
    n3 = s.normal[:h * f, :w_ * f].reshape(h, f, w_, f, 3).mean(axis=(1, 3)).astype(np.float64)
    mask = s.object_mask[:h * f, :w_ * f].reshape(h, f, w_, f).all(axis=(1, 3))
    sigma = 10.0 / f
    w = gaussian_filter(mask.astype(np.float64), sigma)
    inner = mask & (w > 0.9)  # away from the part's outline, where smoothing mixes in the belt
    # the body (part 1) more than 20 frame px (about 2 mm) from any other part (the studs, the plug) and the outline
    body = s.part_index[:h * f, :w_ * f].reshape(h, f, w_, f).min(axis=(1, 3)) == 1
    far = body & (distance_transform_edt(body) * f > 20.0)
    smooth = (gaussian_filter(t * mask, sigma) / np.maximum(w, 1e-9),
              np.stack([gaussian_filter(n3[..., j] * mask, sigma) / np.maximum(w, 1e-9) for j in range(3)], -1))
    for name, (a, b), where in (("pixel", (t, n3), inner), ("10 px", smooth, inner),
                                ("10 px, body far from studs", smooth, inner & far),
                                ("10 px, near studs or outline", smooth, inner & ~far)):
        ts[name].append(a[where])
        ns[name].append(b[where])
    parts += 1
    if parts == want:
        break


def cubic(n):
    """The monomials of the normal's three components up to degree 3 (20 columns, the constant included)."""
    x, y, z = n[:, 0], n[:, 1], n[:, 2]
    return np.stack([x ** i * y ** j * z ** m for i in range(4) for j in range(4 - i) for m in range(4 - i - j)], 1)


fits = {}
for name in ts:  # the regions are read with the fits of all the part's pixels at their scale
    t, n = np.concatenate(ts[name]), np.concatenate(ns[name])
    scale = name.split(",")[0]
    if scale not in fits:
        everything = np.concatenate(ts[scale]), np.concatenate(ns[scale])
        fits[scale] = (tuple(np.polyfit(everything[1][:, 0], everything[0], 1)),
                       np.linalg.lstsq(cubic(everything[1]), everything[0], rcond=None)[0])
    (k, c), beta = fits[scale]
    head = f"{root}: {'unpolarized, ' if unpolarized else ''}{name}"
    for how, residual in (("t = k n_x + c", t - k * n[:, 0] - c), ("t = cubic(n)", t - cubic(n) @ beta)):
        err = np.degrees(np.abs(residual) / abs(k))
        print(f"{head}: {parts} good parts, {t.size} pixels; {how} (k = {k:.3f}); error along x: median "
              f"{np.median(err):.2f} deg, 90th percentile {np.percentile(err, 90):.2f} deg")
