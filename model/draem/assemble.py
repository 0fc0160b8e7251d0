"""The paper's per-prior ensemble assembled from single-prior models trained apart (one per machine, GPU or
night: the members never see each other while training). Each member keeps its own network and normalisation,
so the ensemble scores a part exactly as the average of its members would."""

from __future__ import annotations

from collections.abc import Sequence

from .detector import Detector
from .errors import ModelError
from .preprocess import Normalizer

SHARED_FIELDS = ("reconstructive_width", "discriminative_width", "input_size_px", "score_window_px", "roi")
"""Config fields every member must share: the ensemble runs them on one crop at one size with one score window."""


def assemble_ensemble(members: Sequence[Detector], names: Sequence[str]) -> Detector:
    """One ``fusion = "ensemble"`` detector whose member per prior is the network that sees only that prior in
    ``members`` (a fused model over one prior, or any member of an ensemble), weights and normalisation copied.

    ``names`` (one per detector, e.g. checkpoint paths) only label errors. Priors keep the order they come in.
    Raises ModelError naming the model when one fuses several priors, two give the same prior, or their
    ``SHARED_FIELDS`` differ."""
    if len(members) != len(names) or not members:
        raise ModelError("assemble_ensemble: give one name per detector, at least one detector")
    parts: dict[str, tuple[Detector, str, str]] = {}  # prior -> (detector, its member key, name)
    first = members[0].config
    for det, name in zip(members, names, strict=True):
        cfg = det.config
        differ = [f"{f} {getattr(cfg, f)} vs {getattr(first, f)}" for f in SHARED_FIELDS
                  if getattr(cfg, f) != getattr(first, f)]
        if differ:
            raise ModelError(f"{name}: differs from {names[0]} in {', '.join(differ)}; an ensemble's members share "
                             f"input size, widths, score window and crop")
        for key in det.members:
            priors = cfg.member_priors(key)
            if len(priors) != 1:
                raise ModelError(f"{name}: its network {key!r} reads {len(priors)} priors ({', '.join(priors)}); an "
                                 f"ensemble member reads one (train it with --priors <one> --fusion fused)")
            if priors[0] in parts:
                raise ModelError(f"{name}: prior {priors[0]!r} is already given by {parts[priors[0]][2]}")
            parts[priors[0]] = (det, key, name)
    config = first.with_(priors=tuple(parts), fusion="ensemble", preset=first.preset)
    mean: list[float] = []
    std: list[float] = []
    for det, key, _ in parts.values():
        s = det.member_slice(key)
        mean += det.normalizer.mean[s]
        std += det.normalizer.std[s]
    out = Detector(config, Normalizer(tuple(mean), tuple(std)))
    for prior, (det, key, _) in parts.items():
        out.members[prior].load_state_dict(det.members[key].state_dict())
    return out.eval()

