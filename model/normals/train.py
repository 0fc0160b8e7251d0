"""Training and running the learned normal estimator (``net.NormalUNet``) on rendered ground-truth normals.

Data: one frame's prior maps, viewing directions and ground truth become one square sample through the same
region of interest and resize as the DRAEM station (``model.draem.roi.roi_box``,
``model.draem.preprocess.crop_resize``), so the estimator sees what the detector will see. Loss: mean (1 - cos)
between predicted and true normals over object pixels. Adam, cosine learning-rate decay over the run (by steps,
or by time when only minutes are given), seeded; optional mirror augmentation that is exact for polarization: a
left-right mirror maps AoLP a -> pi - a (sin 2a changes sign) and negates the x of view and normal; an up-down
mirror maps a -> -a and negates y.
Data loading from files is the caller's (this package never reads the renderer's formats).
"""

from __future__ import annotations

import logging
import math
import time
from collections.abc import Mapping
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
import torch

from model.draem.preprocess import crop_resize
from model.draem.roi import roi_box
from model.draem.runtime import resolve_device

from .errors import NormalsError
from .net import NormalNetConfig, NormalUNet, stack_maps
from .sfp import view_directions

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class NormalTrainConfig:
    """``steps`` and/or ``max_minutes`` bound the run (at least one); whichever ends first ends it and the
    learning-rate schedule follows the further along of the two. ``threads``: torch CPU threads, set for the whole
    process with ``torch.set_num_threads`` (None: leave as is). ``flip``: mirror augmentation (module docstring)."""

    steps: int | None = None
    max_minutes: float | None = None
    batch_size: int = 8
    lr: float = 2e-3
    weight_decay: float = 0.0
    seed: int = 0
    device: str = "auto"
    threads: int | None = None
    flip: bool = True

    def __post_init__(self) -> None:
        if self.steps is None and self.max_minutes is None:
            raise NormalsError("normal net training needs steps or max_minutes")
        if (self.steps is not None and self.steps < 1) or (self.max_minutes is not None and self.max_minutes <= 0):
            raise NormalsError(f"normal net training: steps must be >= 1 and max_minutes > 0 ({self})")
        if self.batch_size < 1 or self.lr <= 0:
            raise NormalsError(f"normal net training: batch_size >= 1 and lr > 0 required ({self})")


def prepare_sample(maps: Mapping[str, np.ndarray], object_mask: np.ndarray, size_px: int,
                   fov_x_deg: float | None = None, normal: np.ndarray | None = None, roi: str = "center",
                   extra: tuple[np.ndarray, ...] = ()) -> dict[str, Any]:
    """One frame -> the network's square view of it: ``x`` (7, S, S) inputs, ``mask`` (S, S) object pixels,
    ``normal`` (3, S, S) ground truth (renormalised after resizing; None without ``normal`` (H, W, 3)),
    ``extra``: further (H, W, 3) normal maps (e.g. another estimator's) cropped and resized alike, ``box``.

    ``maps``: "intensity", "dolp", "aolp_cos", "aolp_sin" (H, W) as ``model.priors.compute_priors`` gives them;
    viewing directions are computed exactly for the resized crop from ``fov_x_deg`` (None: orthographic)."""
    om = np.asarray(object_mask, dtype=bool)
    box = roi_box(roi, om.shape, om)
    view = view_directions(om.shape, fov_x_deg, box=box, size=size_px)
    full = stack_maps(maps)
    if full.shape[1:] != om.shape:
        raise NormalsError(f"normal estimator inputs differ in shape: priors {full.shape[1:]}, object mask "
                           f"{om.shape}")
    xt, (mt,) = crop_resize(full, box, size_px, ("intensity", "dolp", "aolp"), (om,))
    x = torch.cat([xt, torch.from_numpy(np.ascontiguousarray(view.transpose(2, 0, 1)))], 0)
    out: dict[str, Any] = {"x": x, "mask": mt, "box": box, "normal": None, "extra": []}
    for key, arr in [("normal", normal), *(("extra", e) for e in extra)]:
        if arr is None:
            continue
        a = np.asarray(arr, dtype=np.float32)
        if a.shape != (*om.shape, 3):
            raise NormalsError(f"normal map {a.shape} must be (H, W, 3) = {(*om.shape, 3)}")
        t, _ = crop_resize(a.transpose(2, 0, 1), box, size_px, ("normal",))
        if key == "normal":
            out["normal"] = t
        else:
            out["extra"].append(t)
    return out


def normal_loss(pred: torch.Tensor, gt: torch.Tensor, mask: torch.Tensor) -> torch.Tensor:
    """Mean (1 - cos angle) over ``mask`` (B, H, W) between (B, 3, H, W) unit normals; 0 for an empty mask."""
    cos = (pred * gt).sum(1)
    m = mask.to(cos.dtype)
    return ((1 - cos) * m).sum() / m.sum().clamp_min(1.0)


def mirror(x: torch.Tensor, normal: torch.Tensor, mask: torch.Tensor, lr: bool, ud: bool
           ) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
    """Mirror a (B, 7, H, W) input batch, its normals and masks left-right and/or up-down, exactly (AoLP, view and
    normal components transformed with the image; see the module docstring)."""
    if lr:
        x, normal, mask = x.flip(-1), normal.flip(-1), mask.flip(-1)
        sign = torch.tensor([1, 1, 1, -1, -1, 1, 1], dtype=x.dtype, device=x.device).view(1, -1, 1, 1)
        x = x * sign
        normal = normal * torch.tensor([-1, 1, 1], dtype=x.dtype, device=x.device).view(1, 3, 1, 1)
    if ud:
        x, normal, mask = x.flip(-2), normal.flip(-2), mask.flip(-2)
        sign = torch.tensor([1, 1, 1, -1, 1, -1, 1], dtype=x.dtype, device=x.device).view(1, -1, 1, 1)
        x = x * sign
        normal = normal * torch.tensor([1, -1, 1], dtype=x.dtype, device=x.device).view(1, 3, 1, 1)
    return x, normal, mask


@dataclass
class TrainResult:
    net: NormalUNet
    steps: int
    seconds: float
    loss_first: float
    loss_last: float
    history: list[tuple[int, float]]
    config: dict[str, Any]


def train_normal_net(x: torch.Tensor, normal: torch.Tensor, mask: torch.Tensor,
                     net_config: NormalNetConfig | None = None, tc: NormalTrainConfig | None = None,
                     progress: bool = True) -> TrainResult:
    """Train a ``NormalUNet`` on (N, 7, S, S) inputs, (N, 3, S, S) unit normals and (N, S, S) object masks.

    Returns the net (eval mode, on CPU) and the loss history (mean of every 10 steps)."""
    from tqdm import tqdm

    tc = tc or NormalTrainConfig(steps=100)
    net_config = net_config or NormalNetConfig(input_size_px=int(x.shape[-1]))
    if x.ndim != 4 or x.shape[1] != net_config.in_channels or normal.shape != (x.shape[0], 3, *x.shape[2:]) or \
            mask.shape != (x.shape[0], *x.shape[2:]):
        raise NormalsError(f"training data: inputs {tuple(x.shape)}, normals {tuple(normal.shape)} and masks "
                           f"{tuple(mask.shape)} do not match as (N, {net_config.in_channels}, S, S) / (N, 3, S, S) "
                           f"/ (N, S, S)")
    if x.shape[0] == 0:
        raise NormalsError("training data is empty")
    if tc.threads:
        torch.set_num_threads(tc.threads)
    device = resolve_device(tc.device)
    torch.manual_seed(tc.seed)
    g = torch.Generator().manual_seed(tc.seed)
    net = NormalUNet(net_config).to(device).train()
    opt = torch.optim.Adam(net.parameters(), lr=tc.lr, weight_decay=tc.weight_decay)
    max_s = tc.max_minutes * 60 if tc.max_minutes is not None else math.inf
    n = x.shape[0]
    history: list[tuple[int, float]] = []
    window: list[float] = []
    first = last = math.nan
    step = 0
    t0 = time.perf_counter()
    bar = tqdm(total=tc.steps, desc="normal net", unit="step", disable=not progress, dynamic_ncols=True)
    try:
        while True:
            elapsed = time.perf_counter() - t0
            frac = max(step / tc.steps if tc.steps else 0.0, elapsed / max_s)
            if frac >= 1:
                break
            for group in opt.param_groups:
                group["lr"] = tc.lr * 0.5 * (1 + math.cos(math.pi * min(frac, 1.0)))
            idx = torch.randint(0, n, (min(tc.batch_size, n),), generator=g)
            xb, nb, mb = x[idx], normal[idx], mask[idx]
            if tc.flip:
                lr_, ud_ = (torch.rand(2, generator=g) < 0.5).tolist()
                xb, nb, mb = mirror(xb, nb, mb, lr_, ud_)
            xb, nb, mb = xb.to(device), nb.to(device), mb.to(device)
            loss = normal_loss(net(xb), nb, mb)
            opt.zero_grad(set_to_none=True)
            loss.backward()
            opt.step()
            step += 1
            value = float(loss.detach())
            if not math.isfinite(value):
                raise NormalsError(f"normal net training diverged at step {step} (loss {value})")
            first = value if step == 1 else first
            window.append(value)
            if len(window) == 10:
                last = sum(window) / len(window)
                history.append((step, last))
                window = []
            bar.update(1)
            bar.set_postfix(loss=f"{value:.4f}", angle=f"{math.degrees(math.acos(max(-1.0, 1 - value))):.1f}",
                            samples_s=f"{step * xb.shape[0] / max(time.perf_counter() - t0, 1e-9):.1f}")
    finally:
        bar.close()
    if window:
        last = sum(window) / len(window)
        history.append((step, last))
    seconds = time.perf_counter() - t0
    log.info("normal net: %d steps in %.1f s, loss %.4f -> %.4f", step, seconds, first, last)
    return TrainResult(net.cpu().eval(), step, seconds, first, last, history,
                       {**asdict(tc), "device": str(device), "n_train": int(n)})


@torch.no_grad()
def predict_normals(net: NormalUNet, x: torch.Tensor, batch_size: int = 16) -> torch.Tensor:
    """(N, 3, S, S) unit normals for (N, 7, S, S) inputs (eval mode, on the net's device, returned on CPU)."""
    net.eval()
    device = next(net.parameters()).device
    out = [net(x[i:i + batch_size].to(device)).cpu() for i in range(0, x.shape[0], batch_size)]
    return torch.cat(out) if out else torch.zeros((0, 3, *x.shape[2:]))
