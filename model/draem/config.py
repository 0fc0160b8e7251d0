"""Model configuration: priors and their channel counts, network widths, input size, named presets.

How a network sees each prior (values before normalisation; conventions in ``model.priors.conventions``):
    intensity  1 channel, unpolarized intensity S0/2 in [0, 1]
    dolp       1 channel, degree of linear polarization in [0, 1]
    aolp       2 channels (cos 2*aolp, sin 2*aolp), a unit vector: AoLP has period pi, so never the raw angle
    normal     3 channels, unit surface normal in camera coordinates (x right, y up, z toward the camera)
    tilt_x     1 channel, the surface's tilt toward the dome's +x segment in [-1, 1], from a frame per segment
    tilt_y     likewise toward +y (``model.priors.photometric``; the model's ``dome_segments`` must give the pair)
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field, replace
from enum import StrEnum
from typing import Any

from model.priors.photometric import check_tilts

from .errors import ModelError

PRIOR_CHANNELS: dict[str, int] = {"intensity": 1, "dolp": 1, "aolp": 2, "normal": 3, "tilt_x": 1, "tilt_y": 1}
"""Input channels per prior, in the order the station stacks them for the fused network."""

ROIS = ("center", "band", "tall", "frame", "object")
"""Regions a network can see: see ``ModelConfig.roi``."""

UNIT_VECTOR_PRIORS = ("aolp", "normal")
"""Priors whose channels form a unit vector per pixel: blended and renormalised as vectors, never clipped."""

SIGNED_PRIORS = ("tilt_x", "tilt_y")
"""Scalar priors in [-1, 1]; the other scalar priors lie in [0, 1] (``value_range``)."""


def value_range(prior: str) -> tuple[float, float]:
    """The values a scalar prior's channel takes: (-1, 1) for ``SIGNED_PRIORS``, else (0, 1)."""
    return (-1.0, 1.0) if prior in SIGNED_PRIORS else (0.0, 1.0)


def check_priors(priors: str | tuple[str, ...] | list[str]) -> tuple[str, ...]:
    """Prior names as a tuple (a comma-separated string is split); raises ModelError on unknown or repeated names."""
    names = tuple(p.strip() for p in priors.split(",")) if isinstance(priors, str) else tuple(priors)
    unknown = [p for p in names if p not in PRIOR_CHANNELS]
    if unknown or not names or len(set(names)) != len(names):
        raise ModelError(f"priors {list(names)}: unknown, empty or repeated; choose from {', '.join(PRIOR_CHANNELS)}")
    return names


def channel_slices(priors: tuple[str, ...]) -> dict[str, slice]:
    """Where each prior's channels lie in the stacked (fused) input tensor."""
    out, start = {}, 0
    for p in priors:
        out[p] = slice(start, start + PRIOR_CHANNELS[p])
        start += PRIOR_CHANNELS[p]
    return out


@dataclass(frozen=True)
class NetworkConfig:
    """One DRAEM network: widths of the two sub-networks, input channels and input size in pixels (height
    ``input_size_px``; width ``input_width_px``, 0 = square).

    Both must be multiples of 32 (the discriminative U-Net pools five times)."""

    in_channels: int = 1
    reconstructive_width: int = 128
    discriminative_width: int = 64
    input_size_px: int = 256
    input_width_px: int = 0

    def __post_init__(self) -> None:
        if self.in_channels < 1 or self.reconstructive_width < 1 or self.discriminative_width < 1:
            raise ModelError(f"network config {self}: channels and widths must be >= 1")
        for side in (self.input_size_px, self.input_width_px or self.input_size_px):
            if side < 32 or side % 32:
                raise ModelError(f"each input side must be a positive multiple of 32, got {self.input_shape}")

    @property
    def input_shape(self) -> tuple[int, int]:
        """(height, width) of the input in pixels."""
        return self.input_size_px, self.input_width_px or self.input_size_px


@dataclass(frozen=True)
class Preset:
    name: str
    reconstructive_width: int
    discriminative_width: int
    input_size_px: int
    note: str = ""


PRESETS: dict[str, Preset] = {
    "paper": Preset("paper", 128, 64, 256, "DRAEM as published (97.4 M parameters for 3 input channels); GPU"),
    "fast": Preset("fast", 32, 16, 128, "1/4 widths at 128 px: ~16x fewer parameters; CPU real time"),
    "lean": Preset("lean", 16, 16, 128, "fast with half its reconstructive width: ~2.5x fewer FLOPs; slow CPUs"),
    "tiny": Preset("tiny", 8, 4, 64, "for tests and smoke runs only"),
}


DECISIONS = ("combined", "variation", "residual")

# The threshold rule's default (``metrics.choose_threshold``, ``adapt``, every command that sets a threshold): at most
# this share of the good validation parts rejected. Issue 19's target rate: defective parts caught at <= 1 % of good
# parts rejected. Until rule 56 (docs/results/2026-11-29-operating-point.md) it was 5 %, where a lens's blur or
# vignetting doubled the false rejects; the 1 % point held.
GOOD_REJECTED_RATE = 0.01


class Alignment(StrEnum):
    """How a fit treats a frame-wide factor: the polarization's gain and turn (``VariationModel.align_polarization``,
    the model file's ``global_polarization`` buffer holds the mode's index) or the log intensity's contrast gain
    (``VariationModel.align_contrast``, read from its ``contrast_range`` buffer). ``OFF`` reads the frame as it is;
    ``MEAN`` puts every frame (the fitted good parts too) onto the good parts' mean by the factor; ``RANGE`` takes out
    only the part of the factor beyond what the fitted good parts showed, so a frame like theirs is judged as without
    alignment (to float rounding)."""

    OFF = "off"
    MEAN = "mean"
    RANGE = "range"

    @property
    def code(self) -> float:
        """The ``global_polarization`` buffer's value: 0 off, 1 mean, 2 range."""
        return float(list(Alignment).index(self))

    @classmethod
    def of(cls, value: Alignment | str | bool, name: str = "global_polarization") -> Alignment:
        """A mode from its name, or from the boolean of files and calls before ``RANGE`` (True: ``MEAN``); a
        ModelError naming ``name`` (the setting) for anything else."""
        if isinstance(value, bool):
            return cls.MEAN if value else cls.OFF
        try:
            return cls(value)
        except ValueError:
            names = ", ".join(m.value for m in cls)
            raise ModelError(f"{name} must be one of {names}, got {value!r}") from None


@dataclass(frozen=True)
class ModelConfig:
    """Everything that defines the detector's architecture: priors, fusion, widths, input size.

    ``fusion``: "ensemble" = one DRAEM per prior, anomaly maps and scores averaged (the paper);
    "fused" = one DRAEM over all priors stacked along channels (ours; cheaper by about the number of priors).
    ``score_window_px``: side of the box filter before the max that gives the image score (DRAEM: 21 at 256 px);
    0 means scale 21 px with the input size (odd, at least 3).
    ``roi``: the region the network sees. "center": the centre square of the frame (the part's known position on
    the line), image score over the whole square; what a station can run. "band": the middle half (in height) of
    the centre square, at twice the centre square's resolution for the same ``input_size_px`` (input
    ``input_size_px`` x 2 ``input_size_px``): for a part longer than wide laid across the view by the fixture, as
    on the shipped line (``model.draem.roi.band_box``); also a station's. "tall": the middle two thirds of the centre
    square at the band's detail (input ``input_size_px`` x 1.5 ``input_size_px``, e.g. 128 x 192; the size a
    multiple of 64): the band with room above and below, so a part turned a few degrees keeps its ends in view
    (``model.draem.roi.tall_box``); also a station's. "frame": the whole frame squeezed to the
    square input (no crop: the region of interest switched off, for comparison; not with the normal prior, whose
    estimator reads the centre square). "object": a square around the rendered object mask, image score on the
    object only; needs ground truth at inference (research upper bound).
    ``variation``: the detector also carries the registered variation model (``model.draem.variation``), fitted on
    good parts after training (``station variation``), and decides on the larger of the two detectors' findings.
    ``decision``: "combined" (that rule) or "variation" (the variation model's finding alone; ``station eval``
    still computes and reports the networks, the station skips them): set by ``station variation --decision``, and
    by ``station adapt`` when the networks are out of their domain on a line (``model.draem.adapt.DOMAIN_SHIFT_SD``);
    "residual" (the residual networks' finding alone, ``model.draem.residual``: set by ``station residual``).
    ``residual_members``: how many residual networks read the variation model's signed z maps (0: none).
    ``frame_aspect``: width / height of the frames the model was trained on (``station train`` reads it from the
    set's manifest; 0: not recorded). On a frame taller than those (the whole sensor, against 4:3 renders) the
    region keeps to the same part of the view (``model.draem.roi``); 0 lays it out on each frame's own shape.
    ``dome_segments``: the azimuths (degrees) of the dome segments the model's frames were taken under, one frame
    per segment per part, in order (photometric stereo, ``model.priors.photometric``; ``station train`` reads them
    from the set's manifest); empty: one frame per part. Intensity and polarization are read from the frames' mean
    (the uniform dome), so a model with segments but no tilt prior still needs its frames.
    ``around_px``: input pixels of the frame around the view the variation model's registration reads at a station
    and in ``station eval`` (``model.draem.variation``, module docstring: around; ``model.draem.roi.AROUND_PX``, which
    ``station variation`` sets, ``station adapt`` keeps when it is given the frame around); 0: the view alone, as every
    file before 2026-12-06; needs the variation model, and neither roi "object" nor the normal prior."""

    priors: tuple[str, ...] = ("intensity", "dolp", "aolp", "normal")
    fusion: str = "ensemble"
    preset: str = "fast"
    reconstructive_width: int = 32
    discriminative_width: int = 16
    input_size_px: int = 128
    score_window_px: int = 0
    roi: str = "center"
    variation: bool = False
    decision: str = "combined"
    residual_members: int = 0
    frame_aspect: float = 0.0
    dome_segments: tuple[float, ...] = ()
    around_px: int = 0
    extra: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        object.__setattr__(self, "priors", check_priors(self.priors))
        if self.fusion not in ("ensemble", "fused"):
            raise ModelError(f"fusion must be 'ensemble' or 'fused', got {self.fusion!r}")
        if self.roi not in ROIS:
            raise ModelError(f"roi must be one of {', '.join(ROIS)}, got {self.roi!r}")
        self.networks()  # each network's config checks its input's sides (multiples of 32)
        if self.roi == "frame" and "normal" in self.priors:  # the band lies inside the square: cut from it
            raise ModelError(f"roi {self.roi!r} cannot take the normal prior: its estimator reads the centre square")
        if self.variation and "intensity" not in self.priors:
            raise ModelError("the variation model registers parts by their intensity: add the intensity prior")
        if self.decision not in DECISIONS or (self.decision == "variation" and not self.variation):
            raise ModelError(f"decision must be one of {', '.join(DECISIONS)} ('variation' needs the variation "
                             f"model), got {self.decision!r}")
        if self.residual_members < 0 or (self.residual_members and not self.variation):
            raise ModelError(f"residual_members must be >= 0 and needs the variation model, got "
                             f"{self.residual_members}")
        if self.decision == "residual" and not self.residual_members:
            raise ModelError("decision 'residual' needs residual networks (residual_members >= 1)")
        if not (isinstance(self.frame_aspect, int | float) and math.isfinite(self.frame_aspect)
                and 0 <= self.frame_aspect <= 100):
            raise ModelError(f"frame_aspect must be 0 (not recorded) or a frame's width / height, got "
                             f"{self.frame_aspect!r}")
        object.__setattr__(self, "dome_segments", tuple(float(a) for a in self.dome_segments))
        try:
            check_tilts(self.priors, self.dome_segments)
        except ValueError as exc:
            raise ModelError(f"priors {list(self.priors)}: {exc}") from None
        if "normal" in self.priors and self.dome_segments:
            raise ModelError("the normal prior's estimator reads one frame; a model of dome segments cannot take it")
        if not isinstance(self.around_px, int) or not 0 <= self.around_px <= 64 or (self.around_px and (
                not self.variation or self.roi == "object" or "normal" in self.priors)):
            raise ModelError(f"around_px must be 0 or, with the variation model, neither roi 'object' nor the "
                             f"normal prior, up to 64 input px; got {self.around_px!r}")
        if self.score_window_px < 0 or (self.score_window_px and self.score_window_px % 2 == 0):
            raise ModelError(f"score_window_px must be 0 (auto) or odd, got {self.score_window_px}")

    @classmethod
    def from_preset(cls, preset: str, priors: tuple[str, ...] | str = ("intensity", "dolp", "aolp", "normal"),
                    fusion: str = "ensemble", input_size_px: int | None = None, roi: str = "center",
                    dome_segments: tuple[float, ...] = ()) -> ModelConfig:
        if preset not in PRESETS:
            raise ModelError(f"unknown preset {preset!r}; known: {', '.join(PRESETS)}")
        p = PRESETS[preset]
        return cls(check_priors(priors), fusion, preset, p.reconstructive_width, p.discriminative_width,
                   input_size_px or p.input_size_px, roi=roi, dome_segments=dome_segments)

    @property
    def score_window(self) -> int:
        if self.score_window_px:
            return self.score_window_px
        w = max(3, round(21 * self.input_size_px / 256))
        return w if w % 2 else w + 1

    @property
    def input_shape(self) -> tuple[int, int]:
        """(height, width) of the network input in pixels: ``input_size_px`` high, twice as wide for roi "band", 1.5
        times for "tall", else square."""
        return self.input_size_px, int({"band": 2, "tall": 1.5}.get(self.roi, 1) * self.input_size_px)

    @property
    def networks_decide(self) -> bool:
        """Whether the networks' finding enters the decision (``decision`` "combined"; "variation" needs the
        variation model, checked above)."""
        return self.decision == "combined"

    @property
    def in_channels(self) -> int:
        return sum(PRIOR_CHANNELS[p] for p in self.priors)

    def networks(self) -> dict[str, NetworkConfig]:
        """Network configs keyed by member name: one per prior (ensemble) or one named "fused"."""
        h, w = self.input_shape
        mk = lambda c: NetworkConfig(c, self.reconstructive_width, self.discriminative_width, h,  # noqa: E731
                                     0 if w == h else w)
        if self.fusion == "fused":
            return {"fused": mk(self.in_channels)}
        return {p: mk(PRIOR_CHANNELS[p]) for p in self.priors}

    def member_priors(self, member: str) -> tuple[str, ...]:
        return self.priors if member == "fused" else (member,)

    def with_(self, **kw: Any) -> ModelConfig:
        return replace(self, **kw)

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["priors"] = list(self.priors)
        if self.dome_segments:
            d["dome_segments"] = list(self.dome_segments)
        else:
            d.pop("dome_segments")  # sidecars of one-frame models stay as they were before the key
        if not self.around_px:
            d.pop("around_px")  # as dome_segments: files that read the view alone stay as they were
        return d

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> ModelConfig:
        try:
            return cls(**{**d, "priors": tuple(d["priors"]), "dome_segments": tuple(d.get("dome_segments") or ())})
        except (TypeError, KeyError) as exc:
            raise ModelError(f"model config {d}: {exc}") from None
