"""A trained detector plus the registered variation model (``model.draem.variation``): fitted on good training
parts, calibrated on good validation parts, networks and normalisation copied unchanged."""

from __future__ import annotations

import torch

from .detector import Detector
from .errors import ModelError
from .variation import network_score


@torch.no_grad()
def add_variation(detector: Detector, good: torch.Tensor, good_object_mask: torch.Tensor | None,
                  val_good: torch.Tensor, batch: int = 16, decision: str = "combined") -> Detector:
    """A copy of ``detector`` with ``config.variation`` set: the variation model fitted on ``good`` (N, C, H, W)
    physical priors of good training parts (``good_object_mask`` (N, H, W): where the part is; None: the whole
    input), then calibrated with both detectors' image scores on ``val_good`` (good validation parts, never the
    training parts: a fitted model scores its own parts low). ``decision``: ``ModelConfig.decision`` of the copy
    (which finding rejects; calibration and member scores do not depend on it)."""
    if detector.config.variation:
        raise ModelError("the detector already has a variation model")
    if len(val_good) < 2:
        raise ModelError(f"calibrating the variation model needs good validation parts, got {len(val_good)}")
    out = Detector(detector.config.with_(variation=True, decision=decision), detector.normalizer)
    missing, unexpected = out.load_state_dict(detector.state_dict(), strict=False)
    assert not unexpected and all(k.startswith("variation.") for k in missing), (missing, unexpected)
    out.eval()
    assert out.variation is not None
    out.variation.fit(good, good_object_mask)
    out.variation.calibrate(*member_scores(out, val_good, batch))  # member scores do not depend on calibration
    out.variation.check()
    return out


@torch.no_grad()
def member_scores(detector: Detector, x: torch.Tensor, batch_size: int = 16) -> tuple[torch.Tensor, torch.Tensor]:
    """(N,) network and (N,) variation image scores of a detector with a variation model, before combining."""
    detector.eval()
    net, var = [], []
    for i in range(0, x.shape[0], batch_size):
        out = detector.predict(x[i:i + batch_size])
        net.append(network_score(out.member_scores).float().cpu())
        var.append(out.member_scores["variation"].float().cpu())
    return torch.cat(net), torch.cat(var)
