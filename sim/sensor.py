"""Camera sensor model: rendered Stokes images -> the raw polarizer mosaic a DoFP camera delivers.

Conventions (mosaic layout, Stokes, angles, full-scale units) are ``model.priors.conventions``; the mosaic is
sampled by ``model.priors.mosaic.stokes_to_mosaic``, never redefined here.

Chain, per pixel (all in full-scale units until the ADC; 1.0 = the largest code of ``bit_depth``):
  1. exposure:  ``S * exposure_gain`` (full scale per unit of rendered radiance; folds exposure time, aperture
     and quantum efficiency into one number).
  1b. vignetting: the lens's relative illumination (``model.priors.lens``), ``cos^4`` of the field angle, scaled
     so the frame's corners get ``1 - vignetting`` of the centre's light (0: none, as the renders' pinhole camera),
     on S0, S1 and S2 alike.
     0.2 at the corners made the shipped model reject 11 % of good parts against 5 %
     (docs/results/2026-11-29-sensor-optics.md).
  1c. lens blur: a Gaussian point spread of ``lens_blur_px`` (sigma, frame px) on S0, S1 and S2 alike, before the
     polarizers, as a lens blurs the light that reaches the polarizer array (0: the render's own sharpness, a box
     pixel filter). The render's fireflies are first brought to full scale (``suppress_fireflies``). A softer image
     also softens the mosaic's false polarization at edges, which blurring the demosaicked frame cannot undo: 0.7 px
     made the shipped model reject 11 % of good parts against 5 % (the same page; measured with the fireflies).
  2. polarizer: ``I(t) = 0.5 * (S0 + e * (S1 cos 2t + S2 sin 2t))`` with ``e = (ER - 1) / (ER + 1)`` for an
     extinction ratio ER (``e = 1`` for an ideal polarizer, ``extinction_ratio=None``).
  3. electrons: ``I * full_scale_e`` with ``full_scale_e = full_well_e / analog_gain``; shot noise is
     Poisson, read noise is Gaussian (``read_noise_e``), the well clips at ``full_well_e``.
  4. ADC: ``round(electrons / full_scale_e * (2**bit_depth - 1)) + black_level_dn``, clipped to the code range;
     uint8 for bit depths <= 8, else uint16 (codes in the low bits, as Mono12/Mono16 cameras deliver).
The noiseless ground truth is the exposed scene Stokes (step 1, before the lens and the polarizer's imperfection)
and the ideal mosaic of step 2.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from model.priors.conventions import get_layout
from model.priors.lens import relative_illumination
from model.priors.mosaic import stokes_to_mosaic

from .errors import SimError

SIZES = {"default": (640, 480), "native": (2448, 2048)}
"""(width, height) of the paper's training images and of the IMX250MZR sensor."""


@dataclass(frozen=True)
class SensorConfig:
    """Sensor parameters; defaults are a Sony IMX250MZR at minimum gain (10.5 ke- full well, 2.3 e- read noise)."""

    bit_depth: int = 8
    exposure_gain: float = 2.0
    full_well_e: float = 10500.0
    read_noise_e: float = 2.3
    analog_gain: float = 1.0
    black_level_dn: int = 0
    extinction_ratio: float | None = None
    lens_blur_px: float = 0.0
    vignetting: float = 0.0
    shot_noise: bool = True
    layout: str = "imx250mzr"

    def __post_init__(self) -> None:
        if self.bit_depth not in (8, 10, 12, 14, 16):
            raise SimError(f"sensor.bit_depth must be 8, 10, 12, 14 or 16, got {self.bit_depth}")
        for key in ("exposure_gain", "full_well_e", "analog_gain"):
            v = getattr(self, key)
            if not (np.isfinite(v) and v > 0):
                raise SimError(f"sensor.{key} must be a positive number, got {v}")
        for key in ("read_noise_e", "lens_blur_px"):
            v = getattr(self, key)
            if not (np.isfinite(v) and v >= 0):
                raise SimError(f"sensor.{key} must be >= 0, got {v}")
        if not 0 <= self.black_level_dn < 2**self.bit_depth - 1:
            raise SimError(f"sensor.black_level_dn must be in [0, {2**self.bit_depth - 1}), got {self.black_level_dn}")
        if not (np.isfinite(self.vignetting) and 0 <= self.vignetting < 1):
            raise SimError(f"sensor.vignetting must be in [0, 1), got {self.vignetting}")
        if self.extinction_ratio is not None and not self.extinction_ratio > 1:
            raise SimError(f"sensor.extinction_ratio must be > 1 (or None for ideal), got {self.extinction_ratio}")
        try:
            get_layout(self.layout)
        except ValueError as exc:
            raise SimError(f"sensor.layout: {exc}") from None

    @property
    def max_code(self) -> int:
        return 2**self.bit_depth - 1

    @property
    def dtype(self) -> type[np.unsignedinteger]:
        return np.uint8 if self.bit_depth <= 8 else np.uint16

    @property
    def full_scale_e(self) -> float:
        """Electrons that make one full scale (the largest code, without black level)."""
        return self.full_well_e / self.analog_gain

    @property
    def polarizer_contrast(self) -> float:
        """``e = (ER - 1) / (ER + 1)``: how much of S1, S2 a real polarizer passes (1 when ideal)."""
        er = self.extinction_ratio
        return 1.0 if er is None else (er - 1.0) / (er + 1.0)


@dataclass(frozen=True)
class SensorFrame:
    """One simulated exposure. ``raw``: (H, W) uint8/uint16 codes of ``bit_depth`` bits. ``ideal``: the noiseless
    float32 mosaic in full-scale units (after exposure, lens and polarizer, before noise and ADC). ``s0, s1, s2``:
    the exposed scene Stokes, float32 full-scale units (the ground truth, before the lens)."""

    raw: np.ndarray
    ideal: np.ndarray
    s0: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    bit_depth: int
    n_saturated: int


def expose(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray, config: SensorConfig
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Rendered Stokes (radiance units) -> exposed Stokes in full-scale units (float32)."""
    g = np.float32(config.exposure_gain)
    return tuple(np.asarray(s, dtype=np.float32) * g for s in (s0, s1, s2))  # type: ignore[return-value]


FIREFLY_RATIO = 10.0
"""A rendered pixel brighter than this many times the median of its ``FIREFLY_WINDOW`` neighbourhood, above
``FULL_SCALE_S0``, and with no neighbour above it, is a firefly (``suppress_fireflies``): one Monte Carlo sample that
found a light. In seed 1157's 400 renders of the shipped line (16 spp): 255 such pixels in 127 renders, one at S0 =
297 (the sensor clips at 2) beside neighbours at 0.65. A highlight is a patch: where it is noisy, bright pixels sit
beside each other (a missing stud's opening: pixels at 20 next to pixels at 1 and at 20), and none of them is taken
for a firefly."""

FIREFLY_WINDOW = 5
"""Side (px) of the neighbourhood whose median ``suppress_fireflies`` compares a pixel with."""

FULL_SCALE_S0 = 2.0
"""S0 (full-scale units) at which unpolarized light fills every polarizer pixel: the sensor clips above it."""


def suppress_fireflies(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Exposed Stokes (full-scale units) -> the same with each firefly (``FIREFLY_RATIO``: a lone pixel far brighter
    than its neighbourhood and above full scale) scaled down to S0 = ``FULL_SCALE_S0``, its DoLP and AoLP kept
    (float32). A sharp sensor clips such a pixel at about that level, so it shows no more of it than this; a lens blur
    of the raw render would spread the sample's whole weight (S0 up to 300) over a patch of clipped pixels, a
    bright spot no real lens shows. Of the shipped file's good parts the 0.7 px lens blur pushed over its threshold on
    seed 1157, 5 of 6 had a firefly within 16 px of their highest place (docs/results/2026-11-29-fireflies.md)."""
    s0 = np.asarray(s0, dtype=np.float32)
    median = cv2.medianBlur(s0, FIREFLY_WINDOW)
    ring = np.ones((3, 3), np.uint8)
    ring[1, 1] = 0
    brightest_neighbour = cv2.dilate(s0, ring, borderType=cv2.BORDER_REFLECT)
    firefly = ((s0 > FULL_SCALE_S0) & (s0 > FIREFLY_RATIO * np.maximum(median, 0.0))
               & (brightest_neighbour <= FULL_SCALE_S0))
    scale = np.where(firefly, FULL_SCALE_S0 / np.where(firefly, s0, 1.0), 1.0).astype(np.float32)
    return tuple(np.asarray(s, dtype=np.float32) * scale for s in (s0, s1, s2))  # type: ignore[return-value]


def lens_blur(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray, sigma_px: float
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Exposed Stokes (full-scale units) through a Gaussian point spread of sigma ``sigma_px`` frame pixels, the
    frame's edges reflected, after the render's fireflies are brought to what a sharp sensor shows of them
    (``suppress_fireflies``); unchanged (the same arrays) at 0. Linear, so it blurs S1 and S2 as the light's
    polarized part is blurred: DoLP at an edge between differently polarized areas drops, as through a lens."""
    if sigma_px <= 0:
        return s0, s1, s2
    return tuple(cv2.GaussianBlur(s, (0, 0), sigma_px, borderType=cv2.BORDER_REFLECT)
                 for s in suppress_fireflies(s0, s1, s2))  # type: ignore[return-value]


def lens(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray, config: SensorConfig
         ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Exposed Stokes (full-scale units) as the lens delivers them to the polarizers: vignetted, then blurred
    (steps 1b-1c); the same arrays when the config has neither."""
    if config.vignetting > 0:
        fall = relative_illumination(*np.shape(s0), config.vignetting)
        s0, s1, s2 = (s * fall for s in (s0, s1, s2))
    return lens_blur(s0, s1, s2, config.lens_blur_px)


def ideal_mosaic(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray, config: SensorConfig) -> np.ndarray:
    """Exposed Stokes (full-scale units) -> noiseless float32 mosaic through the (possibly leaky) polarizers."""
    e = np.float32(config.polarizer_contrast)
    return stokes_to_mosaic(s0, s1 * e, s2 * e, config.layout)


def digitize(ideal: np.ndarray, config: SensorConfig, rng: np.random.Generator) -> np.ndarray:
    """Noiseless mosaic (full-scale units) -> raw codes: shot noise, read noise, full well, ADC (see module doc)."""
    electrons = np.clip(ideal.astype(np.float64), 0.0, None) * config.full_scale_e
    if config.shot_noise:
        electrons = rng.poisson(electrons).astype(np.float64)
    if config.read_noise_e > 0:
        electrons += rng.normal(0.0, config.read_noise_e, size=electrons.shape)
    np.clip(electrons, 0.0, config.full_well_e, out=electrons)
    codes = np.rint(electrons * (config.max_code / config.full_scale_e)) + config.black_level_dn
    return np.clip(codes, 0, config.max_code).astype(config.dtype)


def simulate(s0: np.ndarray, s1: np.ndarray, s2: np.ndarray, config: SensorConfig,
             rng: np.random.Generator) -> SensorFrame:
    """Rendered Stokes images (H, W), radiance units, H and W even -> one ``SensorFrame``.

    Deterministic for a given ``rng`` state (pass ``np.random.default_rng(seed)``).
    """
    s0 = np.asarray(s0)
    if s0.ndim != 2 or s0.shape[0] % 2 or s0.shape[1] % 2 or np.shape(s1) != s0.shape or np.shape(s2) != s0.shape:
        raise SimError(f"Stokes images must be (H, W) with even sides and equal shapes, got "
                       f"{s0.shape}, {np.shape(s1)}, {np.shape(s2)}")
    e0, e1, e2 = expose(s0, s1, s2, config)
    ideal = ideal_mosaic(*lens(e0, e1, e2, config), config)
    raw = digitize(ideal, config, rng)
    n_sat = int(np.count_nonzero(raw >= config.max_code))
    return SensorFrame(raw, ideal, e0, e1, e2, config.bit_depth, n_sat)


def raw_to_fullscale(raw: np.ndarray, config: SensorConfig) -> np.ndarray:
    """Raw codes -> float32 full-scale units, black level removed (the inverse of the ADC step, without noise)."""
    return ((raw.astype(np.float32) - config.black_level_dn) / np.float32(config.max_code)).astype(np.float32)
