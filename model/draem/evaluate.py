"""Held-out evaluation of a DRAEM detector: the data it takes, a synthetic held-out set, and the metrics.

Training (``train.py``) evaluates with it for keep-best; ``station eval``, ``station train``'s final report and
``station quantize``'s check call it on rendered or imported sets. Pixel metrics are computed on the object region
only, and only over samples whose defect mask is known.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import torch

from . import metrics as M
from .anomaly import AnomalyConfig, synthesize
from .detector import Detector
from .runtime import autocast

if TYPE_CHECKING:
    from .train import TrainData


@dataclass
class EvalData:
    """Held-out samples: priors (N, C, S, S), object_mask and defect_mask (N, S, S) bool, label (N,) {0, 1};
    ``kind`` says where the anomalies come from ("rendered" defects or "synthetic"). ``mask_known`` (N,) bool:
    whose defect mask is ground truth (None: all); pixel metrics use only those samples (a defective part without
    a mask is never scored against an all-zero mask). ``around``: (N, C, S + 2 a, S' + 2 a) the priors of the frame
    around each view, which the variation model's registration reads (``Detector.predict``); None: not read."""

    priors: torch.Tensor
    object_mask: torch.Tensor
    defect_mask: torch.Tensor
    label: torch.Tensor
    kind: str = "rendered"
    mask_known: torch.Tensor | None = None
    around: torch.Tensor | None = None


def synthetic_eval_data(good: TrainData, priors: tuple[str, ...], seed: int = 12345, max_samples: int = 256,
                        anomaly: AnomalyConfig | None = None) -> EvalData:
    """A fixed held-out set of DRAEM-style synthetic anomalies on good samples (half of them anomalous)."""
    n = min(len(good), max_samples)
    x, obj = good.get(torch.arange(n))
    g = torch.Generator().manual_seed(seed)
    syn = synthesize(x, priors, g, anomaly or AnomalyConfig(), obj)
    return EvalData(syn.augmented, obj, syn.mask.bool(), syn.label.long(), "synthetic")


@dataclass
class EvalResult:
    """metrics: image/pixel AUROC, pixel AP, AUPRO (FPR <= 0.3), image F1-max and its threshold, per-member image
    AUROC; scores: (N,) image scores; maps: (N, S, S) anomaly maps (CPU float32); member_scores / member_maps: the
    same per ensemble member (empty for a single network), for ablations over subsets of members."""

    metrics: dict[str, float]
    scores: np.ndarray
    maps: np.ndarray
    member_scores: dict[str, np.ndarray] = field(default_factory=dict)
    member_maps: dict[str, np.ndarray] = field(default_factory=dict)


@torch.no_grad()
def evaluate(detector: Detector, data: EvalData, batch_size: int = 16, device: torch.device | None = None,
             precision: str = "fp32", channels_last: bool = False) -> EvalResult:
    """Run ``detector`` over ``data`` and compute the metrics (pixel metrics on the object region only)."""
    device = device or next(detector.parameters()).device
    was_training = detector.training
    detector.eval()
    maps, scores, member_scores, member_maps = [], [], {}, {}
    for i in range(0, data.priors.shape[0], batch_size):
        x = data.priors[i:i + batch_size].to(device)
        obj = data.object_mask[i:i + batch_size].to(device)
        if channels_last:
            x = x.contiguous(memory_format=torch.channels_last)
        with autocast(device, precision):  # roi "center": scored over the whole square, as at a station
            around = None if data.around is None else data.around[i:i + batch_size].to(device)
            out = detector.predict(x, obj if detector.config.roi == "object" else None, around=around)
        maps.append(out.anomaly_map.float().cpu())
        scores.append(out.score.float().cpu())
        for k, v in out.member_scores.items():
            member_scores.setdefault(k, []).append(v.float().cpu())
            member_maps.setdefault(k, []).append(out.member_maps[k].float().cpu())
    detector.train(was_training)
    amap = torch.cat(maps).numpy()
    score = torch.cat(scores).numpy()
    label = data.label.numpy().astype(bool)
    known = None if data.mask_known is None else data.mask_known.numpy().astype(bool)
    res = M.summary(label, score, amap, data.defect_mask.numpy(), data.object_mask.numpy(), known)
    if len(member_scores) <= 1:
        return EvalResult(res, score, amap)
    ms = {k: torch.cat(v).numpy() for k, v in member_scores.items()}
    for k, v in ms.items():
        res[f"image_auroc_{k}"] = M.auroc(label, v)
    return EvalResult(res, score, amap, ms, {k: torch.cat(v).numpy() for k, v in member_maps.items()})
