"""Mixed supervision: training batches of good parts with DRAEM's synthetic anomalies plus rendered defective parts
with their true masks (issue 19, point 1).

A batch of ``B`` samples holds ``B - R`` good samples, drawn and augmented exactly as DRAEM (``anomaly.synthesize``:
half of them get a Perlin-masked synthetic anomaly), followed by ``R`` rendered defective samples
(``TrainConfig.n_rendered``). Synthetic anomalies stay in every batch on purpose: a segmenter trained on rendered
defects alone scored an unseen defect type at chance (docs/model.md), and the station must catch kinds of defect
nobody rendered.

Targets of a rendered sample (input = the defective render):
    discriminative   its true defect mask
    reconstruction   its paired clean render (same scene without the defect) when the data has one: the published
                     loss, as for a synthetic anomaly; otherwise the input itself with the reconstruction loss
                     weighted 0 on the defect (and, for SSIM, within its 11x11 window): the network is taught to
                     pass the part through unchanged outside the defect and is told nothing about what lies under it
With ``R = 0`` the batch is drawn exactly as before this module existed (same generator calls, same values).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import torch

from .anomaly import AnomalyConfig, synthesize
from .errors import ModelError
from .polarization_noise import add_polarization_noise


class GoodData(Protocol):
    """Good training samples (``train.TrainData``): (B, C, S, S) priors, (B, S, S) bool object masks."""

    def __len__(self) -> int: ...

    def get(self, indices: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]: ...


class DefectData(Protocol):
    """Rendered defective training samples at the network input size. ``get(indices)`` returns
    (priors (B, C, S, S) float32 physical values, object_mask (B, S, S) bool, defect_mask (B, S, S) bool,
    clean (B, C, S, S) float32 or None): ``clean`` is a paired render of the same scene without the defect, for
    the whole batch or None. ``TensorDefectData`` holds them in memory; a streamed source needs these two methods."""

    def __len__(self) -> int: ...

    def get(self, indices: torch.Tensor
            ) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor, torch.Tensor | None]: ...


@dataclass
class TensorDefectData:
    """In-memory rendered defects: priors (N, C, S, S) float32, object_mask and defect_mask (N, S, S) bool,
    clean (N, C, S, S) float32 paired defect-free renders or None."""

    priors: torch.Tensor
    object_mask: torch.Tensor
    defect_mask: torch.Tensor
    clean: torch.Tensor | None = None

    def __post_init__(self) -> None:
        n = self.priors.shape[0] if self.priors.ndim == 4 else -1
        mask_shape = (n, *self.priors.shape[2:])
        if n < 0 or self.object_mask.shape != mask_shape or self.defect_mask.shape != mask_shape:
            raise ModelError(f"defect data: priors {tuple(self.priors.shape)}, object masks "
                             f"{tuple(self.object_mask.shape)} and defect masks {tuple(self.defect_mask.shape)} do "
                             f"not match as (N, C, S, S) / (N, S, S) / (N, S, S)")
        if self.clean is not None and self.clean.shape != self.priors.shape:
            raise ModelError(f"defect data: clean renders {tuple(self.clean.shape)} differ from the defective "
                             f"ones {tuple(self.priors.shape)}")

    def __len__(self) -> int:
        return self.priors.shape[0]

    def get(self, indices: torch.Tensor
            ) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor, torch.Tensor | None]:
        clean = None if self.clean is None else self.clean[indices]
        return self.priors[indices], self.object_mask[indices].bool(), self.defect_mask[indices].bool(), clean


@dataclass
class TrainBatch:
    """One training batch in physical units, on the training device. inputs: (B, C, S, S) what the network sees;
    target: (B, C, S, S) what it should reconstruct; mask: (B, S, S) float {0, 1} discriminative target;
    recon_weight: (B, S, S) float per-pixel weight of the reconstruction loss, or None (weight 1 everywhere,
    the published loss); n_rendered: the last ``n_rendered`` samples are rendered defects."""

    inputs: torch.Tensor
    target: torch.Tensor
    mask: torch.Tensor
    recon_weight: torch.Tensor | None
    n_rendered: int = 0


def n_rendered(rendered_fraction: float, batch_size: int) -> int:
    """Rendered samples per batch: ``rendered_fraction x batch_size`` rounded half up; raises ModelError unless
    0 <= fraction < 1 and, for a fraction > 0, the batch keeps at least one rendered and one synthetic sample."""
    if not 0.0 <= rendered_fraction < 1.0:
        raise ModelError(f"rendered_fraction must be in [0, 1) (synthetic anomalies stay in every batch), "
                         f"got {rendered_fraction}")
    n = int(rendered_fraction * batch_size + 0.5)
    if rendered_fraction > 0 and not 1 <= n <= batch_size - 1:
        raise ModelError(f"rendered_fraction {rendered_fraction} x batch_size {batch_size} gives {n} rendered "
                         f"samples per batch; it must give 1 .. {batch_size - 1}")
    return n


def draw_batch(data: GoodData, priors: tuple[str, ...], batch_size: int, index_gen: torch.Generator,
               synth_gen: torch.Generator, anomaly: AnomalyConfig, device: torch.device,
               defects: DefectData | None = None, rendered: int = 0,
               defect_gen: torch.Generator | None = None, polarization_noise: float = 0.0) -> TrainBatch:
    """Draw one batch: ``batch_size - rendered`` good samples (indices from ``index_gen``) with DRAEM's synthesis
    (``synth_gen``, on ``device``), then ``rendered`` samples of ``defects`` (indices from ``defect_gen``, CPU).
    ``rendered = 0`` makes exactly the calls and values of the loop before mixed supervision.
    ``polarization_noise`` > 0: every input (good and rendered) gets Stokes noise up to that level
    (``polarization_noise.py``, drawn from ``synth_gen``); the reconstruction targets stay the clean parts, so
    the networks learn that the noise level is not a defect."""
    n_syn = batch_size - rendered
    idx = torch.randint(len(data), (n_syn,), generator=index_gen)
    x, obj = data.get(idx)
    x, obj = x.to(device, non_blocking=True), obj.to(device, non_blocking=True)
    x_in = add_polarization_noise(x, priors, polarization_noise, synth_gen)
    syn = synthesize(x_in, priors, synth_gen, anomaly, obj)
    if rendered == 0:
        return TrainBatch(syn.augmented, x, syn.mask, None, 0)
    if defects is None or defect_gen is None or len(defects) == 0:
        raise ModelError(f"{rendered} rendered samples per batch asked for, but no rendered defects given")
    ridx = torch.randint(len(defects), (rendered,), generator=defect_gen)
    xr, _, mr, cr = defects.get(ridx)
    if xr.shape[1:] != x.shape[1:] or mr.shape != (rendered, *x.shape[2:]):
        raise ModelError(f"rendered defects {tuple(xr.shape)} / masks {tuple(mr.shape)} do not match the good "
                         f"samples {tuple(x.shape)}")
    xr, mr = xr.to(device, x.dtype), mr.to(device).bool()
    xr_in = add_polarization_noise(xr, priors, polarization_noise, synth_gen)
    mask = torch.cat([syn.mask, mr.to(syn.mask.dtype)])
    if cr is not None:
        return TrainBatch(torch.cat([syn.augmented, xr_in]), torch.cat([x, cr.to(device, x.dtype)]), mask, None,
                          rendered)
    weight = torch.cat([torch.ones_like(syn.mask), (~mr).to(syn.mask.dtype)])
    return TrainBatch(torch.cat([syn.augmented, xr_in]), torch.cat([x, xr]), mask, weight, rendered)
