"""Detectability numerics: a defect's signal in each prior against the sensor's noise (pure numpy, no rendering).

Inputs are noiseless *exposed* Stokes images (full-scale units, ``sim.sensor.expose``) of the same scene with and
without the defect. Conventions: ``model.priors.conventions`` (intensity = S0 / 2 in full-scale units, DoLP in
[0, 1], AoLP in radians with period pi, counted from image right toward image up); normals are unit vectors in
camera coordinates (``sim.scene``).

Noise (analytic, first-order error propagation; not Monte Carlo): a pixel behind the polarizer at angle t reads
``I_t = 0.5 * (S0 + e * (S1 cos 2t + S2 sin 2t))`` (``e``: the polarizer contrast of ``SensorConfig``) with variance,
in full-scale units squared,

    v_t = I_t / full_scale_e                  shot noise (Poisson electrons)
        + (read_noise_e / full_scale_e)^2     read noise
        + 1 / (12 * max_code^2)               ADC rounding (uniform over one code)

A 2x2 superpixel reads the four angles once each, independently. A prior p(I_0, I_45, I_90, I_135) then has
``var_superpixel(p) = sum_t (dp/dI_t)^2 v_t``. Each camera pixel carries a quarter of a superpixel's
information, so the noise of a prior *per pixel of area* is ``std_pixel = 2 * std_superpixel``: for intensity
this is the std of one raw pixel's reading (4 * sum_t v_t / 16 = mean v_t), and summing ``(d / std_pixel)^2``
over pixels equals summing ``(d / std_superpixel)^2`` over superpixels for a difference ``d`` that is smooth over
2x2 pixels. The ADC term is the usual uniform-rounding approximation, valid when the other noise is at least about
one code (at 8 bit on dark faces it is not exact). Where any polarizer pixel of either render reaches full scale
(the well or the ADC clips), the prior carries no information: std = inf there, which drops those pixels. AoLP's
std is capped at ``AOLP_STD_CAP`` (the std of an angle uniform over its period): where (S1, S2) is near zero the
linearisation fails and AoLP is a coin toss. A test checks the analytic std against Monte Carlo draws of
``sim.sensor.digitize``.

Normal (from the rendered ground truth, the learned normal prior's upper bound): the difference is the angle
between the two renders' normals, and its std per pixel is the AoLP std (a normal estimated from polarization
takes its azimuth from AoLP, so it is no better known than that); capped like AoLP.

Matched-filter SNR of a difference ``d`` with per-pixel std ``s`` over the defect pixels M:
``SNR = sqrt(sum_M (d / s)^2)``. Rendering noise adds to ``d`` and would inflate ``d^2`` (a good part compared
with itself would score > 0), so the oracle renders the pair twice with independent Mitsuba seeds (``d_a``,
``d_b``) and uses ``sum_M d_a * d_b / s^2``, an unbiased estimate of ``sum_M E[d]^2 / s^2`` (independent noise
averages out of the product), clipped at 0 before the square root.
"""

from __future__ import annotations

import numpy as np

from model.priors.conventions import POLARIZER_ANGLES_DEG

from .sensor import SensorConfig

CAMERA_PRIORS = ("intensity", "dolp", "aolp")
"""Priors a polarization camera measures (the oracle's "best prior" is the best of these)."""
PRIORS = (*CAMERA_PRIORS, "normal")
POLARIZATION_PRIORS = ("dolp", "aolp")
AOLP_STD_CAP = float(np.pi / np.sqrt(12))
"""Std (radians) of an angle uniform over AoLP's period pi: the most an AoLP (or normal) can be unknown."""
_TINY = 1e-12


def polarizer_intensities(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray, contrast: float = 1.0) -> np.ndarray:
    """(4, ...) intensities behind polarizers at 0, 45, 90, 135 degrees: ``0.5 * (S0 + e (S1 cos 2t + S2 sin 2t))``,
    full-scale units, ``e`` = ``contrast``."""
    t = np.radians(np.asarray(POLARIZER_ANGLES_DEG, dtype=np.float64)).reshape((4,) + (1,) * np.ndim(s0))
    return 0.5 * (np.asarray(s0, np.float64) + contrast * (np.asarray(s1, np.float64) * np.cos(2 * t)
                                                           + np.asarray(s2, np.float64) * np.sin(2 * t)))


def reading_variance(intensity: np.ndarray, sensor: SensorConfig) -> np.ndarray:
    """Variance (full-scale units squared) of one raw pixel reading of mean ``intensity`` (full-scale units): shot +
    read + ADC rounding (see the module docstring)."""
    fs = sensor.full_scale_e
    shot = np.clip(intensity, 0.0, None) / fs if sensor.shot_noise else 0.0 * intensity
    return shot + (sensor.read_noise_e / fs) ** 2 + 1.0 / (12.0 * sensor.max_code**2)


def measured_stokes(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray, sensor: SensorConfig
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The Stokes the camera measures from exposed scene Stokes: S1, S2 scaled by the polarizer contrast."""
    e = sensor.polarizer_contrast
    return np.asarray(s0, np.float64), np.asarray(s1, np.float64) * e, np.asarray(s2, np.float64) * e


def prior_values(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray) -> dict[str, np.ndarray]:
    """Noiseless camera priors (float64) from measured Stokes: intensity = S0 / 2, DoLP = |(S1, S2)| / S0 (0 where
    S0 <= 0), AoLP = 0.5 atan2(S2, S1) (radians)."""
    p = np.hypot(s1, s2)
    return {"intensity": 0.5 * s0, "dolp": np.where(s0 > _TINY, p / np.maximum(s0, _TINY), 0.0),
            "aolp": 0.5 * np.arctan2(s2, s1)}


def prior_std(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray, sensor: SensorConfig) -> dict[str, np.ndarray]:
    """Per-pixel-of-area noise std of each prior (``2 * std_superpixel``, see the module docstring) at exposed
    Stokes ``s0, s1, s2`` (full-scale units); intensity in full-scale units, DoLP unitless, AoLP and normal in
    radians. inf where a polarizer pixel saturates."""
    i = polarizer_intensities(s0, s1, s2, sensor.polarizer_contrast)
    v = reading_variance(i, sensor)
    m0, m1, m2 = measured_stokes(s0, s1, s2, sensor)
    p = np.hypot(m1, m2)
    safe_p = np.maximum(p, _TINY)
    c1 = np.where(p > _TINY, m1 / safe_p, np.sqrt(0.5))
    c2 = np.where(p > _TINY, m2 / safe_p, np.sqrt(0.5))
    s0_safe = np.maximum(m0, _TINY)
    rho = p / s0_safe
    # d/dI_t of S0 = (1, 1, 1, 1) / 2, S1 = (1, 0, -1, 0), S2 = (0, 1, 0, -1), in the order 0, 45, 90, 135
    d_s1 = np.array([1.0, 0.0, -1.0, 0.0]).reshape((4,) + (1,) * m0.ndim)
    d_s2 = np.array([0.0, 1.0, 0.0, -1.0]).reshape((4,) + (1,) * m0.ndim)
    g_int = np.full_like(v, 0.25)
    g_dolp = (c1 * d_s1 + c2 * d_s2) / s0_safe - rho / (2 * s0_safe)
    g_aolp = 0.5 * (m1 * d_s2 - m2 * d_s1) / np.maximum(p * p, _TINY)
    out = {}
    for name, g in (("intensity", g_int), ("dolp", g_dolp), ("aolp", g_aolp)):
        out[name] = 2.0 * np.sqrt(np.sum(g * g * v, axis=0))
    # per-area std of a uniform angle is 2x the cap; where (S1, S2) vanishes AoLP is undefined: the cap too
    out["aolp"] = np.where(p > _TINY, np.minimum(out["aolp"], 2.0 * AOLP_STD_CAP), 2.0 * AOLP_STD_CAP)
    out["normal"] = out["aolp"]
    saturated = np.any(i >= 1.0, axis=0)
    for name in out:
        out[name] = np.where(saturated, np.inf, out[name])
    return out


def prior_differences(a: dict[str, np.ndarray], b: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """``a - b`` per prior: plain for intensity and DoLP, on the circle for AoLP (wrapped to [-pi/2, pi/2)),
    the angle between unit normals (radians, >= 0) for ``normal`` (when both have it)."""
    out = {"intensity": a["intensity"] - b["intensity"], "dolp": a["dolp"] - b["dolp"],
           "aolp": np.angle(np.exp(2j * (a["aolp"] - b["aolp"]))) / 2}
    if "normal" in a and "normal" in b:
        out["normal"] = np.arccos(np.clip(np.sum(np.asarray(a["normal"], np.float64) * b["normal"], axis=-1),
                                          -1.0, 1.0))
    return out


def matched_snr(d_a: np.ndarray, d_b: np.ndarray, std: np.ndarray, mask: np.ndarray) -> float:
    """``sqrt(max(0, sum_mask d_a * d_b / std^2))``: the matched-filter SNR from two independently rendered
    differences (pass ``d_b = d_a`` for a noiseless one). Pixels with infinite std count 0; an empty mask gives 0."""
    sel = np.asarray(mask, bool) & np.isfinite(std)
    if not sel.any():
        return 0.0
    s2 = np.maximum(std[sel], _TINY) ** 2
    return float(np.sqrt(max(0.0, float(np.sum(d_a[sel] * d_b[sel] / s2)))))
