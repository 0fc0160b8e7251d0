"""Frames unlike the renders, as functions on a model's stacked priors: the changes another renderer, lens or camera
makes to them (``shift``), for ``station bench shift`` to measure and for the variation model's fit to learn from
(``blurred_copies``).

Each shift is a pure function on the stacked priors at the model's input (after the region crop and resize:
``model.draem.config.channel_slices``), with the project's conventions (``model.priors.conventions``): intensity in
full-scale units, DoLP in [0, 1], AoLP as (cos 2a, sin 2a), a counted counter-clockwise from image right. numpy and
OpenCV; finite wherever the input is."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .config import channel_slices

SHIFTS = ("none", "dolp x0.5", "dolp x2", "aolp +5 deg", "gamma 0.8", "gamma 1.25", "exposure x1.3", "blur 0.5 px",
          "blur 1 px", "move 2 px", "rotate 5 deg", "zoom x1.05")
"""Every shift ``station bench shift`` runs by default, by name (``shift``)."""


@dataclass(frozen=True)
class Channels:
    """Where intensity, DoLP and AoLP's (cos, sin) lie in a model's input (None when it does not read the prior)."""

    intensity: int | None
    dolp: int | None
    aolp: int | None

    @classmethod
    def of(cls, priors: tuple[str, ...]) -> Channels:
        s = channel_slices(priors)
        return cls(*(s[p].start if p in s else None for p in ("intensity", "dolp", "aolp")))


def _stokes(x: np.ndarray, ch: Channels) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(N, C, H, W) priors -> S0, S1, S2 (N, H, W): S1, S2 = I DoLP (cos 2a, sin 2a)."""
    i = x[:, ch.intensity] if ch.intensity is not None else np.ones(x[:, 0].shape, np.float32)
    p = x[:, ch.dolp] if ch.dolp is not None else np.zeros_like(i)
    c, s = (x[:, ch.aolp], x[:, ch.aolp + 1]) if ch.aolp is not None else (np.ones_like(i), np.zeros_like(i))
    return i, i * p * c, i * p * s


def _from_stokes(x: np.ndarray, ch: Channels, s0: np.ndarray, s1: np.ndarray, s2: np.ndarray) -> np.ndarray:
    """Write S0, S1, S2 back as the model's priors, as the camera's priors are computed (``model.priors.stokes``:
    DoLP in [0, 1] and 0 on dark pixels; AoLP (1, 0) where it is undefined)."""
    from model.priors.stokes import aolp_vector, dolp

    out = x.copy()
    if ch.intensity is not None:
        out[:, ch.intensity] = s0
    if ch.dolp is not None:
        out[:, ch.dolp] = dolp(s0, s1, s2)
    if ch.aolp is not None:
        out[:, ch.aolp], out[:, ch.aolp + 1] = aolp_vector(s1, s2)
    return out


KINDS = ("none", "dolp", "aolp", "gamma", "exposure", "blur", "move", "rotate", "zoom")
SIGNED = ("aolp", "move", "rotate")
"""Kinds whose number may be negative."""


def parse(name: str) -> list[tuple[str, float]]:
    """A shift's name -> its steps (kind, number), in order: "dolp x2" -> [("dolp", 2.0)], "none" -> [("none", 0.0)],
    "dolp x0.7 & blur 0.25 px" -> [("dolp", 0.7), ("blur", 0.25)] (several changes at once, as another renderer
    makes them); ValueError naming the shift otherwise (an unknown kind, a missing or non-finite number)."""
    return [_step(step, name) for step in name.split("&")]


def _step(step: str, name: str) -> tuple[str, float]:
    kind, _, value = step.strip().partition(" ")
    try:
        number = 0.0 if kind == "none" else float(value.split()[0].lstrip("x+"))
    except (IndexError, ValueError):
        number = math.nan
    if (kind not in KINDS or not math.isfinite(number) or (kind not in SIGNED and number < 0)
            or (kind == "zoom" and number == 0)):
        raise ValueError(f"unknown shift {name!r}: e.g. {', '.join(SHIFTS)}, or several joined by '&'")
    return kind, number


def shift(name: str, x: np.ndarray, ch: Channels) -> np.ndarray:
    """``x`` (N, C, H, W) float32 priors changed by shift ``name`` (``SHIFTS``); finite wherever ``x`` is:
    - ``dolp xK``: DoLP times K, clipped to 1 (a material or renderer that polarizes less or more, or a polarizer
      array with another extinction ratio);
    - ``aolp +D deg``: AoLP plus D degrees (the polarizer grid mounted rotated, or another angle convention);
    - ``gamma G``: intensity I -> I^G (another tone response; a camera that is not linear);
    - ``exposure xK``: the four polarizer readings times K, each clipped at full scale 1, and the priors again from
      them (a brighter line: where a reading clips, DoLP falls);
    - ``blur S px``: a Gaussian of sigma S input pixels over S0, S1 and S2 (a softer lens or another
      anti-aliasing; polarization blurs linearly in the Stokes vector, not in DoLP or AoLP);
    - ``move D px``: the part D input pixels to the right (a fixture or camera mounted elsewhere, another renderer's
      pixel-centre convention);
    - ``rotate D deg``: the part turned D degrees counter-clockwise about the input's centre, and its polarization
      with it (AoLP plus D: the angle is counted from image right);
    - ``zoom xK``: the part K times larger about the input's centre (the camera closer, another focal length).
    The geometric ones resample S0, S1, S2 bilinearly (edges replicated) and write the priors back from them.
    Several joined by "&" are applied in the order given."""
    import cv2

    x = np.nan_to_num(np.asarray(x, np.float32), nan=0.0, posinf=1.0, neginf=0.0)
    steps = parse(name)
    if len(steps) > 1:
        for step in name.split("&"):
            x = shift(step, x, ch)
        return x
    kind, number = steps[0]
    if kind == "none":
        return x.copy()
    out = x.copy()
    if kind == "dolp" and ch.dolp is not None:
        out[:, ch.dolp] = np.clip(x[:, ch.dolp] * number, 0.0, 1.0)
    elif kind == "aolp" and ch.aolp is not None:
        t = math.radians(2 * number)
        c, s = x[:, ch.aolp], x[:, ch.aolp + 1]
        out[:, ch.aolp], out[:, ch.aolp + 1] = c * math.cos(t) - s * math.sin(t), c * math.sin(t) + s * math.cos(t)
    elif kind == "gamma" and ch.intensity is not None:
        out[:, ch.intensity] = np.clip(x[:, ch.intensity], 0.0, None) ** number
    elif kind == "exposure" and ch.intensity is not None:
        # the four polarizer readings (the brightest is I (1 + DoLP)), scaled and clipped at full scale, then the
        # Stokes vector again from them; the camera's Stokes are twice these (intensity is S0 / 2)
        from model.priors.conventions import POLARIZER_ANGLES_DEG
        from model.priors.stokes import intensities_to_stokes, stokes_to_intensity

        s0, s1, s2 = (2 * number * a for a in _stokes(x, ch))
        angles = np.radians(POLARIZER_ANGLES_DEG)
        readings = np.stack([np.clip(stokes_to_intensity(s0, t, s1, s2), 0.0, 1.0) for t in angles])
        out = _from_stokes(x, ch, *(intensities_to_stokes(readings) / 2))
    elif kind == "blur":
        s0, s1, s2 = (np.stack([cv2.GaussianBlur(im, (0, 0), number, borderType=cv2.BORDER_REPLICATE) for im in a])
                      for a in _stokes(x, ch))
        out = _from_stokes(x, ch, s0, s1, s2)
    elif kind in ("move", "rotate", "zoom"):
        h, w = x.shape[2:]
        if kind == "move":
            m = np.array([[1.0, 0.0, number], [0.0, 1.0, 0.0]])
        else:  # OpenCV's positive angle turns the image counter-clockwise as displayed (y down)
            m = cv2.getRotationMatrix2D(((w - 1) / 2, (h - 1) / 2), number if kind == "rotate" else 0.0,
                                        number if kind == "zoom" else 1.0)
        s0, s1, s2 = (np.stack([cv2.warpAffine(im, m, (w, h), flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)
                                for im in a]) for a in _stokes(x, ch))
        if kind == "rotate":  # (S1, S2) turn by twice the angle
            t = math.radians(2 * number)
            s1, s2 = s1 * math.cos(t) - s2 * math.sin(t), s1 * math.sin(t) + s2 * math.cos(t)
        out = _from_stokes(x, ch, s0, s1, s2)
    return np.nan_to_num(out, nan=0.0, posinf=1.0, neginf=0.0).astype(np.float32)


def blurred_copies(x: np.ndarray, ch: Channels, max_sigma: float, seed: int = 0) -> np.ndarray:
    """One copy of each of ``x`` (N, C, H, W) priors blurred as ``shift``'s ``blur S px`` does, S drawn uniform in
    [0, ``max_sigma``] input px per part (``np.random.default_rng(seed)``, rounded to 1e-4 px; S = 0 leaves the part
    unchanged): good parts as a softer lens or another renderer's pixel filter would show them, for the variation
    model's fit (``VariationModel.fit``'s ``blur_copies_sigma``). Deterministic for a given seed."""
    if not (math.isfinite(max_sigma) and max_sigma >= 0):
        raise ValueError(f"blurred copies: max_sigma must be finite and >= 0, got {max_sigma}")
    x = np.asarray(x, np.float32)
    sigmas = np.random.default_rng(seed).uniform(0.0, max_sigma, len(x))
    return np.concatenate([shift(f"blur {s:.4f} px", x[i:i + 1], ch) if s > 0 else x[i:i + 1]
                           for i, s in enumerate(sigmas)]) if len(x) else x.copy()
