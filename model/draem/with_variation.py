"""A trained detector plus the registered variation model (``model.draem.variation``): fitted on good training
parts, calibrated on good validation parts, networks and normalisation copied unchanged."""

from __future__ import annotations

import torch

from .detector import Detector
from .errors import ModelError


@torch.no_grad()
def add_variation(detector: Detector, good: torch.Tensor, good_object_mask: torch.Tensor | None,
                  val_good: torch.Tensor, batch: int = 16) -> Detector:
    """A copy of ``detector`` with ``config.variation`` set: the variation model fitted on ``good`` (N, C, H, W)
    physical priors of good training parts (``good_object_mask`` (N, H, W): where the part is; None: the whole
    input), then calibrated with both detectors' image scores on ``val_good`` (good validation parts, never the
    training parts: a fitted model scores its own parts low)."""
    if detector.config.variation:
        raise ModelError("the detector already has a variation model")
    if len(val_good) < 2:
        raise ModelError(f"calibrating the variation model needs good validation parts, got {len(val_good)}")
    out = Detector(detector.config.with_(variation=True), detector.normalizer)
    missing, unexpected = out.load_state_dict(detector.state_dict(), strict=False)
    assert not unexpected and all(k.startswith("variation.") for k in missing), (missing, unexpected)
    out.eval()
    assert out.variation is not None
    out.variation.fit(good, good_object_mask)
    net_scores, var_scores = [], []
    for i in range(0, len(val_good), batch):
        x = val_good[i:i + batch]
        net_scores.append(detector.eval().predict(x).score.cpu())
        var_scores.append(out.variation.zmaps(x)[1].cpu())
    out.variation.calibrate(torch.cat(net_scores), torch.cat(var_scores))
    out.variation.check()
    return out
