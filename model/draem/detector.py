"""The detector: one DRAEM per prior (the paper's ensemble) or one over all priors stacked (fused), with the
normalisation and image scoring that belong to it. Input is physical prior values at the network's input size."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import torch
import torch.nn.functional as F
from torch import nn

from .config import ModelConfig, channel_slices
from .errors import ModelError
from .frame_checks import MAX_HIDDEN, NOISE_CAP
from .networks import Draem, DraemEvalOutput, init_weights
from .preprocess import Normalizer
from .residual import UNJUDGEABLE_Z, ResidualDetector, ResidualOutput
from .variation import VariationModel, VariationOutput, combine, squash


def image_scores(anomaly_map: torch.Tensor, object_mask: torch.Tensor | None, window_px: int) -> torch.Tensor:
    """DRAEM's image score: max of the ``window_px`` box-averaged anomaly map, here over the object region.

    anomaly_map: (N, H, W) in [0, 1]; object_mask: (N, H, W) bool or None (whole image). The map is zeroed
    outside the object before averaging (background is not inspected), and the max is taken over object pixels.
    An empty object mask falls back to the whole image. Returns (N,) float32."""
    m = anomaly_map.float().unsqueeze(1)
    if object_mask is None:
        obj = torch.ones_like(m, dtype=torch.bool)
    else:
        obj = object_mask.bool().unsqueeze(1)
        empty = ~obj.flatten(1).any(1)
        obj = obj | empty.view(-1, 1, 1, 1)
    avg = F.avg_pool2d(m * obj, window_px, stride=1, padding=window_px // 2)
    return torch.where(obj, avg, torch.zeros_like(avg)).flatten(1).amax(1)


@dataclass
class DetectorOutput:
    """anomaly_map: (N, H, W) mean of the members' maps; score: (N,) mean of the members' image scores;
    member_maps / member_scores keyed by member (prior name, or "fused"); frame_checks: (N,) per frame, what the
    variation model's rules found (``model.draem.frame_checks.FRAME_CHECKS``),
    empty without that model."""

    anomaly_map: torch.Tensor
    score: torch.Tensor
    member_maps: dict[str, torch.Tensor]
    member_scores: dict[str, torch.Tensor]
    frame_checks: dict[str, torch.Tensor] = field(default_factory=dict)


class Detector(nn.Module):
    """DRAEM members keyed by prior (ensemble) or "fused", plus the input ``Normalizer`` over all channels."""

    def __init__(self, config: ModelConfig, normalizer: Normalizer | None = None):
        super().__init__()
        self.config = config
        self.normalizer = normalizer or Normalizer.identity(config.in_channels)
        if len(self.normalizer.mean) != config.in_channels:
            raise ModelError(f"normalizer has {len(self.normalizer.mean)} channels, model {config.in_channels}")
        self.members = nn.ModuleDict({name: Draem(cfg) for name, cfg in config.networks().items()})
        self._slices = channel_slices(config.priors)
        start = {p: sl.start for p, sl in self._slices.items()}
        self.variation = (VariationModel(config.in_channels, config.input_shape, start["intensity"],
                                         start.get("dolp"), start.get("aolp")) if config.variation else None)
        self.residual = (ResidualDetector(config.in_channels, config.residual_members) if config.residual_members
                         else None)

    def member_slice(self, member: str) -> slice:
        """Channels of the stacked input that member ``member`` sees."""
        if member == "fused":
            return slice(0, self.config.in_channels)
        return self._slices[member]

    def init_weights(self, generator: torch.Generator | None = None) -> None:
        init_weights(self, generator)

    def normalize(self, x: torch.Tensor) -> torch.Tensor:
        return self.normalizer(x)

    @torch.no_grad()
    def predict(self, x: torch.Tensor, object_mask: torch.Tensor | None = None,
                members: Sequence[str] | None = None, around: torch.Tensor | None = None) -> DetectorOutput:
        """x: (N, C, S, S) physical priors stacked as ``config.channel_slices``; object_mask: (N, S, S) bool;
        ``members``: run only these (default all), and average over them; ``around``: the priors of the frame around
        each view, which the variation model's registration reads (``VariationModel.zmaps``)."""
        if x.ndim != 4 or x.shape[1] != self.config.in_channels:
            raise ModelError(f"detector input must be (N, {self.config.in_channels}, H, W) for priors "
                             f"{self.config.priors}, got {tuple(x.shape)}")
        z = self.normalize(x)
        maps, scores = {}, {}
        for name in self.members if members is None else members:
            out = self.members[name](z[:, self.member_slice(name)])
            assert isinstance(out, DraemEvalOutput), "predict needs eval mode: call detector.eval()"
            maps[name] = out.anomaly_map.float()
            scores[name] = image_scores(maps[name], object_mask, self.config.score_window)
        return self.output(x, maps, scores, around)

    def output(self, x: torch.Tensor, maps: dict[str, torch.Tensor], scores: dict[str, torch.Tensor],
               around: torch.Tensor | None = None) -> DetectorOutput:
        """The detector's answer from its networks' maps and scores on physical input ``x``: their mean, combined
        with the variation model's finding when the model has one (``model.draem.variation.combine``; its map and
        score join the member outputs as "variation"). No network output is needed when the variation model alone
        decides (``ModelConfig.decision``): the station skips them then."""
        if maps:
            amap = torch.stack(list(maps.values())).mean(0)
            score = torch.stack(list(scores.values())).mean(0)
        elif not self.config.networks_decide:
            amap, score = x.new_zeros((x.shape[0], *x.shape[2:])), x.new_zeros(x.shape[0])  # not read by combine
        else:
            raise ModelError("no network ran, and the model's decision needs them")
        if self.variation is None:
            return DetectorOutput(amap, score, maps, scores)
        v = self.variation.zmaps(x, signed=self.residual is not None, around=around)
        looks = self.residual is not None and self.residual.looks and self.config.decision != "residual"
        if looks:
            v = self.residual_look(v)
        maps, scores = {**maps, "variation": v.maps}, {**scores, "variation": v.scores}
        if self.residual is not None and not looks:
            assert v.signed is not None and v.judged is not None  # asked for above
            r = self.residual_output(v.signed, v.judged)
            maps["residual"], scores["residual"] = r.map.to(amap.device), r.score.to(score.device)
        if self.config.decision == "residual":
            unjudgeable = ((v.noise_level > NOISE_CAP) | (v.highlight_fraction > MAX_HIDDEN)).to(score.device)
            amap = squash(maps["residual"])
            score = squash(torch.where(unjudgeable, scores["residual"].clamp_min(UNJUDGEABLE_Z), scores["residual"]))
        else:
            amap, score = combine(amap, score, v.maps.to(amap.device), v.scores.to(score.device),
                                  self.variation.calibration, networks=self.config.networks_decide)
        return DetectorOutput(amap, score, maps, scores, v.frame_checks())

    def residual_output(self, signed: torch.Tensor, judged: torch.Tensor) -> ResidualOutput:
        """The residual networks on the variation model's ``signed`` (N, C, H, W) and ``judged`` (N, H, W) maps:
        map (N, H, W) probability, score (N,) robust SD above the good validation parts."""
        assert self.residual is not None
        return self.residual.predict(*self.residual_inputs(signed, judged))

    def residual_look(self, v: VariationOutput) -> VariationOutput:
        """``v`` with the variation model's scores given the residual networks as its second look
        (``model.draem.residual``, ``look``): a part above the second look's gate scores the larger of its score and
        the networks' finding in the window's units; the networks run on those parts only. The rest keep their score.
        With a blend (``ResidualDetector.blends``) the networks run on every part, each scores ``blended``, and
        ``look_level`` is each part's finding over its blend threshold (a frame check)."""
        assert self.residual is not None and self.variation is not None and v.signed is not None
        look = self.variation.second_look
        window = v.maps.flatten(1).amax(1)
        if self.residual.blends:
            assert v.judged is not None
            found = self.look_finding(self.residual.top_logits(*self.residual_inputs(v.signed, v.judged)))
            return v._replace(scores=self.residual.blend_score(v.scores, window, found).to(v.scores.dtype),
                              look_level=self.residual.look_level(found))
        ask = [i for i, w in enumerate(window.tolist()) if look.suspicious(w)]
        if not ask:
            return v
        assert v.judged is not None
        found = self.look_finding(self.residual.top_logits(*self.residual_inputs(v.signed[ask], v.judged[ask])))
        scores = v.scores.clone()
        scores[ask] = torch.maximum(scores[ask], found.to(scores.dtype).to(scores.device))
        return v._replace(scores=scores)

    def look_finding(self, top_logits: torch.Tensor) -> torch.Tensor:
        """(N,) the residual networks' ``top_logits`` -> (N,) their finding as the second look, in the window's units
        (``ResidualDetector.look_score`` in robust SD, back through the second look's ``from_window_sd``), float64."""
        assert self.residual is not None and self.variation is not None
        return self.variation.second_look.from_window_sd(self.residual.look_score(top_logits))

    def residual_inputs(self, signed: torch.Tensor, judged: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """(the residual networks' input (N, C + 2, H, W), (N, H, W) the pixels they judge: ``judged`` inside the
        variation model's region eroded by 1 px, as its own statistic)."""
        assert self.residual is not None and self.variation is not None
        x = self.residual.inputs(signed, self.variation.region.bool(), self.variation.window_spread)
        return x, judged.bool() & torch.from_numpy(self.variation.scored_region()).to(judged.device)
