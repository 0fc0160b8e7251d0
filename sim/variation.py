"""Line variation: how a real line's frames differ from one another beyond the scene's draws (``[variation]``).

A preset's ``[scene]`` ranges already draw the belt's colour and gloss (``background_colour``, the ground's
material and roughness), stray light (``light_*``) and the part's pose. What a scene cannot draw is the camera's
side of the line: the exposure drifts (lamp ageing, a changed exposure time, a dirty dome: +-30 % is what a line
sees between services) and the sensor's noise level changes with the gain a user sets. ``LineVariation`` draws
those per sample from its own random stream (``default_rng([seed, index, 3])``), so a set without variation
renders exactly as before and the scene of sample ``i`` is the same with or without it (``panel_scale``, below,
changes the panel's radiance in it and nothing else).

Units: ``exposure_scale`` multiplies ``SensorConfig.exposure_gain`` (full scale per unit of rendered radiance);
``analog_gain`` is the sensor's (linear; 2 = +6 dB): fewer electrons per code, so more shot noise at the same
brightness. A bright exposure clips highlights at the sensor's full well, as a real camera does.
``panel_scale`` multiplies the scene's ``ring_radiance`` (a bright-field panel or ring light beside the dome): one
lamp that ages or is replaced while the others do not, which no exposure draws (a panel at half its radiance
rejected three times the good parts of the shipped model fitted without it:
docs/results/2026-11-29-panel-brightness.md). It is drawn after exposure and gain from the same stream, so their
draws are the same with or without it.
``lens_blur_px`` draws the sensor's ``lens_blur_px`` (sigma of the lens's Gaussian point spread, frame px, before the
polarizers; ``sim.sensor``): lenses, apertures and focus differ between lines and drift on one, and any real lens is
softer than the renders' box filter. ``vignetting`` draws the sensor's ``vignetting`` (the share of light the frame's
corners lose through the lens, ``sim.sensor``): lenses and apertures differ, and a dome or panel lights a part less
evenly than the renders' uniform one. Each is drawn after the ones before it in the stream (exposure, gain, panel,
blur, vignetting), so every earlier draw is the same with or without it. Their ranges may start at 0.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields, replace
from typing import Any

import numpy as np

from .errors import SimError
from .sensor import SensorConfig

FROM_ZERO = ("lens_blur_px", "vignetting")
"""The ranges that may start at 0 (none of it); the others are factors, above 0."""


@dataclass(frozen=True)
class LineVariation:
    """Per-sample ranges ``(lo, hi)``, uniform draws; the defaults draw nothing (every sample as the sensor)."""

    exposure_scale: tuple[float, float] = (1.0, 1.0)
    """Multiplies the sensor's ``exposure_gain``: e.g. (0.7, 1.3) for +-30 % exposure."""
    analog_gain: tuple[float, float] | None = None
    """The sensor's analog gain (linear, >= 1); None = the sensor's own."""
    panel_scale: tuple[float, float] | None = None
    """Multiplies the scene's ``ring_radiance`` (the panel); None = the scene's own (``sim.dataset.draw_sample``)."""
    lens_blur_px: tuple[float, float] | None = None
    """The sensor's ``lens_blur_px`` (frame px, >= 0); None = the sensor's own."""
    vignetting: tuple[float, float] | None = None
    """The sensor's ``vignetting`` (share of light lost at the corners, in [0, 1)); None = the sensor's own."""

    def __post_init__(self) -> None:
        for f in fields(self):
            v = getattr(self, f.name)
            if v is None:
                continue
            from_zero = f.name in FROM_ZERO
            if (not isinstance(v, tuple) or len(v) != 2 or not all(np.isfinite(x) for x in v)
                    or not (v[0] >= 0 if from_zero else v[0] > 0) or v[0] > v[1]
                    or (f.name == "vignetting" and v[1] >= 1)):
                bound = "0 <= lo" if from_zero else "0 < lo"
                raise SimError(f"variation.{f.name}: need a range [lo, hi] with {bound} <= hi"
                               f"{' < 1' if f.name == 'vignetting' else ''}, got {v!r}")

    @property
    def active(self) -> bool:
        return self != LineVariation()

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> LineVariation:
        known = {f.name for f in fields(cls)}
        bad = sorted(set(d) - known)
        if bad:
            raise SimError(f"variation: unknown keys {bad}; known: {', '.join(sorted(known))}")
        return cls(**{k: tuple(v) if isinstance(v, list) else v for k, v in d.items()})

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        for key in ("panel_scale", *FROM_ZERO):
            if d[key] is None:
                d.pop(key)  # manifests of sets rendered before the key stay as they were
        return d

    def _stream(self, seed: int, index: int) -> tuple[float, float | None, float | None, float | None, float | None]:
        """Sample ``index``'s (exposure scale, analog gain, panel scale, lens blur, vignetting; each None when its
        range is not set but the first), in the stream's order."""
        rng = np.random.default_rng([seed, index, 3])
        scale = float(rng.uniform(*self.exposure_scale))
        rest = [float(rng.uniform(*r)) if r else None
                for r in (self.analog_gain, self.panel_scale, self.lens_blur_px, self.vignetting)]
        return scale, rest[0], rest[1], rest[2], rest[3]

    def draw(self, sensor: SensorConfig, seed: int, index: int) -> tuple[SensorConfig, dict[str, float]]:
        """The sensor of sample ``index``, and what was drawn for it (for ``params.json``'s ``sensor``); the sensor
        unchanged and ``{}`` when nothing varies."""
        if not self.active:
            return sensor, {}
        scale, gain, _, blur, vignetting = self._stream(seed, index)
        gain = sensor.analog_gain if gain is None else gain
        drawn = replace(sensor, exposure_gain=sensor.exposure_gain * scale, analog_gain=gain)
        record = {"exposure_scale": scale, "exposure_gain": drawn.exposure_gain, "analog_gain": gain}
        for key, value in (("lens_blur_px", blur), ("vignetting", vignetting)):
            if value is not None:
                drawn = replace(drawn, **{key: value})
                record[key] = value
        return drawn, record

    def panel(self, seed: int, index: int) -> float | None:
        """Sample ``index``'s factor on the scene's ``ring_radiance`` (None when ``panel_scale`` is not set)."""
        return self._stream(seed, index)[2] if self.panel_scale else None
