"""The detectability oracle: render a defective sample's scene again without its defect and measure, per prior, how
far the defect stands above the sensor's noise (numerics and conventions: ``sim.visibility``).

Pairs: the scene with the defect (``defect.model``) and without it (the good ``model``), same camera, light,
materials and Mitsuba seed, so every path that never meets the defect takes the same random decisions and the two
images agree there to float precision. Two pairs with independent seeds (the sample's Mitsuba seed and a second one
derived from it) give two independent differences whose product removes the rendering noise from the SNR
(``sim.visibility.matched_snr``). Each render is at ``spp`` (the caller's choice; the dataset uses half the sample's
spp, so the four renders cost about two sample renders).

Two domains:
  ``snr``           priors of each rendered pixel's noiseless Stokes (what the optics put on the sensor);
  ``snr_demosaic``  priors as the station computes them: the noiseless 2x2 mosaic of each render through the
                    bilinear demosaic (``model.priors.demosaic``), against the noise ``sim.visibility.prior_std``
                    gives for the demosaiced Stokes (a pixel next to a highlight gets its neighbours' light and
                    their shot noise); pixels with a saturated mosaic pixel in their 3x3 neighbourhood are left
                    out. The ratio of the two is what mosaic sampling and interpolation do to a defect of that size.
                    Caveat: at a few spp the rendering noise of neighbouring pixels leaks into the demosaiced S1, S2
                    (as scene texture does at the camera), which scrambles AoLP where DoLP is low.
Both sum over the defect's visible pixels (the sample's ``defect_mask``); changes outside it (a shadow the missing
stud no longer casts) are not counted. A defect with no visible pixel has SNR 0 in every prior and is not rendered
again.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field

import numpy as np

from .defects import DefectResult
from .meshes import ObjectModel
from .render import RenderOutput, RenderSettings, render_sample
from .sensor import SensorConfig, expose, ideal_mosaic
from .visibility import CAMERA_PRIORS, PRIORS, matched_snr, prior_differences, prior_std, prior_values

SECOND_SEED_OFFSET = 0x9E3779B9
"""The second pair's Mitsuba seed is the sample's plus this (mod 2^32)."""


@dataclass(frozen=True)
class DefectSNR:
    """Matched-filter SNR per prior (``sim.visibility.PRIORS``) of one defect, in both domains (see the module
    docstring); ``best`` is the camera prior (intensity, DoLP, AoLP) with the largest ``snr``; ``pixels`` the
    defect's visible pixels; ``spp`` of each oracle render; ``seconds`` spent rendering and measuring."""

    snr: dict[str, float]
    snr_demosaic: dict[str, float]
    best: str
    pixels: int
    spp: int
    seconds: float = 0.0
    extra: dict[str, float] = field(default_factory=dict)

    @property
    def best_snr(self) -> float:
        return self.snr[self.best]

    def to_dict(self) -> dict:
        d = asdict(self)
        d["best_snr"] = self.best_snr
        d["snr"] = {k: round(v, 4) for k, v in d["snr"].items()}
        d["snr_demosaic"] = {k: round(v, 4) for k, v in d["snr_demosaic"].items()}
        d["seconds"] = round(d["seconds"], 3)
        if not d["extra"]:
            d.pop("extra")
        return d


def zero_snr(spp: int = 0) -> DefectSNR:
    """The oracle's answer for a defect with no visible pixel."""
    return DefectSNR({p: 0.0 for p in PRIORS}, {p: 0.0 for p in CAMERA_PRIORS}, CAMERA_PRIORS[0], 0, spp)


def best_prior(snr: dict[str, float]) -> str:
    """The camera prior with the largest SNR (intensity on ties)."""
    return max(CAMERA_PRIORS, key=lambda p: (snr[p], -CAMERA_PRIORS.index(p)))


def _exposed(out: RenderOutput, sensor: SensorConfig) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    return expose(out.s0, out.s1, out.s2, sensor)


def _maps(stokes: tuple[np.ndarray, np.ndarray, np.ndarray], sensor: SensorConfig) -> dict[str, np.ndarray]:
    s0, s1, s2 = (np.asarray(s, np.float64) for s in stokes)
    e = sensor.polarizer_contrast
    return prior_values(s0, s1 * e, s2 * e)


def _demosaic(stokes: tuple[np.ndarray, np.ndarray, np.ndarray], sensor: SensorConfig
              ) -> tuple[dict[str, np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray], np.ndarray]:
    """The station's view of a noiseless render: the 2x2 mosaic (clipped at full scale, as the sensor clips) through
    the bilinear demosaic. Returns its priors, its Stokes (S1, S2 divided by the polarizer contrast again, so
    ``prior_std`` can take them) and where a mosaic pixel of its 3x3 neighbourhood is saturated."""
    import cv2

    from model.priors.demosaic import mosaic_to_stokes

    ideal = ideal_mosaic(*stokes, sensor)
    s0, s1, s2 = mosaic_to_stokes(np.clip(ideal, 0.0, 1.0).astype(np.float32), sensor.layout, "bilinear", True)
    s0, s1, s2 = (np.asarray(x, np.float64) for x in (s0, s1, s2))
    e = sensor.polarizer_contrast
    near_sat = cv2.dilate((ideal >= 1.0).astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
    return prior_values(s0, s1, s2), (s0, s1 / e, s2 / e), near_sat


def _pair_std(good: tuple, bad: tuple, sensor: SensorConfig) -> dict[str, np.ndarray]:
    """Per-pixel std from the mean variance of the two renders (inf where either saturates)."""
    a, b = prior_std(*good, sensor), prior_std(*bad, sensor)
    return {k: np.sqrt(0.5 * (a[k] ** 2 + b[k] ** 2)) for k in a}


def snr_from_pairs(pairs: list[tuple[RenderOutput, RenderOutput]], mask: np.ndarray, sensor: SensorConfig
                   ) -> tuple[dict[str, float], dict[str, float]]:
    """(snr, snr_demosaic) per prior from one or two (defective, good) render pairs of the same scene. With two
    pairs of independent seeds the product of their differences is used (unbiased); with one, its square (biased
    upward by the rendering noise). The normal's difference comes from the first pair's ground truth (its 1-spp
    AOV pass is the same in every render of a pixel, so it has no rendering noise)."""
    diffs, dem, stds, dem_stds = [], [], [], []
    for bad_out, good_out in pairs:
        bad, good = _exposed(bad_out, sensor), _exposed(good_out, sensor)
        mb, mg = _maps(bad, sensor), _maps(good, sensor)
        diffs.append(prior_differences(mb, mg))
        stds.append(_pair_std(good, bad, sensor))
        (db, sb, nb), (dg, sg, ng) = _demosaic(bad, sensor), _demosaic(good, sensor)
        dem.append(prior_differences(db, dg))
        dem_stds.append({k: np.where(nb | ng, np.inf, v) for k, v in _pair_std(sg, sb, sensor).items()})
    std = {k: np.sqrt(np.mean([s[k] ** 2 for s in stds], axis=0)) for k in stds[0]}
    dem_std = {k: np.sqrt(np.mean([s[k] ** 2 for s in dem_stds], axis=0)) for k in dem_stds[0]}
    a, b = diffs[0], diffs[-1]
    snr = {p: matched_snr(a[p], b[p], std[p], mask) for p in CAMERA_PRIORS}
    snr_dem = {p: matched_snr(dem[0][p], dem[-1][p], dem_std[p], mask) for p in CAMERA_PRIORS}
    bad0, good0 = pairs[0]
    if bad0.normal is not None and good0.normal is not None:
        dn = prior_differences({**_maps(_exposed(bad0, sensor), sensor), "normal": bad0.normal},
                               {**_maps(_exposed(good0, sensor), sensor), "normal": good0.normal})["normal"]
        snr["normal"] = matched_snr(dn, dn, std["normal"], mask)
    else:
        snr["normal"] = 0.0
    return snr, snr_dem


WINDOW_SIZES = (64, 128, 256, 512)
"""Window sides (pixels) the oracle renders: each new film size compiles new kernels, so sides are rounded up to
one of these (or the image's side)."""
WINDOW_MARGIN_PX = 8
"""Pixels kept around the defect's bounding box (the bilinear demosaic reads 1 pixel around each)."""


def defect_window(mask: np.ndarray, margin: int = WINDOW_MARGIN_PX) -> tuple[int, int, int, int]:
    """(x0, y0, w, h) of the block the oracle renders around ``mask``'s pixels (non-empty): the bounding box grown by
    ``margin``, each side rounded up to one of ``WINDOW_SIZES`` (capped at the image), centred on the box and kept
    inside the image, with even x0, y0 (the mosaic's 2x2 phase stays the full image's)."""
    height, width = mask.shape
    ys, xs = np.nonzero(mask)
    out = []
    for lo, hi, side in ((xs.min(), xs.max(), width), (ys.min(), ys.max(), height)):
        need = int(hi - lo + 1 + 2 * margin)
        size = next((s for s in WINDOW_SIZES if s >= need), side)
        size = min(size, side)
        start = round(float(lo + hi + 1) / 2 - size / 2)
        start = min(max(start, 0), side - size)
        start -= start % 2
        out.append((start, size))
    (x0, w), (y0, h) = out
    return x0, y0, w, h


def defect_snr(model: ObjectModel, params: dict, defect: DefectResult, settings: RenderSettings, seed: int,
               sensor: SensorConfig, mask: np.ndarray | None = None) -> tuple[DefectSNR, np.ndarray]:
    """Render two (defective, good) pairs of ``params``' scene at ``settings`` (its spp) with Mitsuba seeds
    ``seed`` and ``seed + SECOND_SEED_OFFSET`` and measure the defect (``sim.visibility``). Only the block around
    the defect is rendered (``defect_window``: the same pixels as the full image's, at a fraction of the cost).
    ``mask``: the defect's visible pixels in the full image (the sample's ``defect_mask``); None = from a 1-spp
    shape-index pass. Returns the result and the full-image mask; a mask with no pixel returns ``zero_snr``
    without rendering the pairs."""
    t0 = time.perf_counter()
    if mask is None:
        probe = RenderSettings(settings.width, settings.height, 1, False, settings.max_depth,
                               settings.background_size_m, settings.variant)
        mask = render_sample(model, params, defect, probe, seed).defect_mask
    if not mask.any():
        return zero_snr(settings.spp), mask
    win = defect_window(mask)
    x0, y0, w, h = win
    gt, plain = (RenderSettings(settings.width, settings.height, settings.spp, g, settings.max_depth,
                                settings.background_size_m, settings.variant, win) for g in (True, False))
    seeds = (int(seed) & 0xFFFFFFFF, (int(seed) + SECOND_SEED_OFFSET) & 0xFFFFFFFF)
    pairs = [(render_sample(model, params, defect, settings_, s), render_sample(model, params, None, settings_, s))
             for settings_, s in ((gt, seeds[0]), (plain, seeds[1]))]
    snr, snr_dem = snr_from_pairs(pairs, mask[y0:y0 + h, x0:x0 + w], sensor)
    return DefectSNR(snr, snr_dem, best_prior(snr), int(mask.sum()), settings.spp,
                     time.perf_counter() - t0), mask
