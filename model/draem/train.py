"""Training DRAEM detectors on in-memory or streamed prior tensors, with held-out evaluation and keep-best.

Recipe as published: Adam (lr 1e-4), learning rate x0.2 at 80 % and 90 % of the steps, loss L2 + SSIM + focal
(``loss.py``), synthetic anomalies on half the samples (``anomaly.py``). The ensemble (one DRAEM per prior) trains
all members in one loop on the same batches and the same synthetic masks; members share no parameters, so one Adam
over all of them is the same as one Adam each. Every ``eval_every`` steps the detector is evaluated on held-out
data and checkpointed; the best image AUROC is kept (it swings over training, see NOTES), the last is kept for
resuming. Data loading is the caller's: this module never reads files of the renderer.
"""

from __future__ import annotations

import contextlib
import logging
import math
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Protocol

import numpy as np
import torch

from . import metrics as M
from .anomaly import AnomalyConfig, synthesize
from .checkpoint import load_checkpoint, paths, save_checkpoint
from .config import ModelConfig
from .detector import Detector
from .errors import CheckpointError, ModelError
from .loss import draem_loss
from .networks import DraemTrainOutput
from .preprocess import Normalizer

log = logging.getLogger(__name__)


class TrainData(Protocol):
    """Good training samples at the network input size: ``get(indices)`` returns (B, C, S, S) float32 physical
    priors and (B, S, S) bool object masks. ``TensorData`` holds them in memory; a streamed source only needs
    these two methods."""

    def __len__(self) -> int: ...

    def get(self, indices: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]: ...


@dataclass
class TensorData:
    """In-memory training data: priors (N, C, S, S) float32, object_mask (N, S, S) bool."""

    priors: torch.Tensor
    object_mask: torch.Tensor

    def __post_init__(self) -> None:
        if self.priors.ndim != 4 or self.object_mask.shape != (self.priors.shape[0], *self.priors.shape[2:]):
            raise ModelError(f"training data: priors {tuple(self.priors.shape)} and object masks "
                             f"{tuple(self.object_mask.shape)} do not match as (N, C, S, S) / (N, S, S)")

    def __len__(self) -> int:
        return self.priors.shape[0]

    def get(self, indices: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        return self.priors[indices], self.object_mask[indices].bool()


@dataclass
class EvalData:
    """Held-out samples: priors (N, C, S, S), object_mask and defect_mask (N, S, S) bool, label (N,) {0, 1};
    ``kind`` says where the anomalies come from ("rendered" defects or "synthetic")."""

    priors: torch.Tensor
    object_mask: torch.Tensor
    defect_mask: torch.Tensor
    label: torch.Tensor
    kind: str = "rendered"


def synthetic_eval_data(good: TrainData, priors: tuple[str, ...], seed: int = 12345, max_samples: int = 256,
                        anomaly: AnomalyConfig | None = None) -> EvalData:
    """A fixed held-out set of DRAEM-style synthetic anomalies on good samples (half of them anomalous)."""
    n = min(len(good), max_samples)
    x, obj = good.get(torch.arange(n))
    g = torch.Generator().manual_seed(seed)
    syn = synthesize(x, priors, g, anomaly or AnomalyConfig(), obj)
    return EvalData(syn.augmented, obj, syn.mask.bool(), syn.label.long(), "synthetic")


@dataclass(frozen=True)
class TrainConfig:
    """steps: optimiser steps; eval_every: steps between evaluation + checkpoint; precision: "fp32", "bf16"
    (autocast) or "auto" (fp32 on CPU: bf16 autocast was measured slower on this AVX2-only CPU, see docs/model.md;
    bf16 on CUDA); channels_last: None = on. ``max_minutes`` stops early (after a final checkpoint)."""

    steps: int = 2000
    batch_size: int = 8
    lr: float = 1e-4
    lr_milestones: tuple[float, float] = (0.8, 0.9)
    lr_gamma: float = 0.2
    seed: int = 0
    eval_every: int = 250
    eval_batch_size: int = 16
    device: str = "auto"
    precision: str = "auto"
    channels_last: bool | None = None
    max_minutes: float | None = None
    anomaly: AnomalyConfig = field(default_factory=AnomalyConfig)

    def __post_init__(self) -> None:
        if self.steps < 1 or self.batch_size < 1 or self.eval_every < 1:
            raise ModelError(f"train config: steps, batch_size and eval_every must be >= 1 ({self})")
        if self.precision not in ("auto", "fp32", "bf16"):
            raise ModelError(f"precision must be auto, fp32 or bf16, got {self.precision!r}")


def resolve_device(device: str) -> torch.device:
    if device == "auto":
        return torch.device("cuda" if torch.cuda.is_available() else "cpu")
    try:
        return torch.device(device)
    except RuntimeError as exc:
        raise ModelError(f"device {device!r}: {exc}") from None


def resolve_precision(precision: str, device: torch.device) -> str:
    if precision != "auto":
        return precision
    return "bf16" if device.type == "cuda" and torch.cuda.is_bf16_supported() else "fp32"


def autocast(device: torch.device, precision: str) -> contextlib.AbstractContextManager:
    if precision == "bf16":
        return torch.autocast(device.type, dtype=torch.bfloat16)
    return contextlib.nullcontext()


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
            out = detector.predict(x, obj if detector.config.roi == "object" else None)
        maps.append(out.anomaly_map.float().cpu())
        scores.append(out.score.float().cpu())
        for k, v in out.member_scores.items():
            member_scores.setdefault(k, []).append(v.float().cpu())
            member_maps.setdefault(k, []).append(out.member_maps[k].float().cpu())
    detector.train(was_training)
    amap = torch.cat(maps).numpy()
    score = torch.cat(scores).numpy()
    label = data.label.numpy().astype(bool)
    gt = data.defect_mask.numpy().astype(bool)
    obj = data.object_mask.numpy().astype(bool)
    f1, f1_t = M.f1_max(label, score)
    res = {
        "image_auroc": M.auroc(label, score), "pixel_auroc": M.pixel_auroc(gt, amap, obj),
        "pixel_ap": M.pixel_ap(gt, amap, obj), "aupro_0.3": M.aupro(gt, amap, 0.3, obj),
        "image_f1_max": f1, "image_f1_threshold": f1_t, "n": int(label.size), "n_anomalous": int(label.sum()),
    }
    if len(member_scores) <= 1:
        return EvalResult(res, score, amap)
    ms = {k: torch.cat(v).numpy() for k, v in member_scores.items()}
    for k, v in ms.items():
        res[f"image_auroc_{k}"] = M.auroc(label, v)
    return EvalResult(res, score, amap, ms, {k: torch.cat(v).numpy() for k, v in member_maps.items()})


@dataclass
class TrainResult:
    best_path: Path
    last_path: Path
    best_metrics: dict[str, float]
    history: list[dict[str, Any]]
    steps_done: int
    seconds: float


def _better(new: dict[str, float], old: dict[str, float] | None) -> bool:
    if old is None:
        return True
    key = lambda m: tuple(-math.inf if math.isnan(m.get(k, math.nan)) else m[k]  # noqa: E731
                          for k in ("image_auroc", "pixel_auroc"))
    return key(new) > key(old)


def train(config: ModelConfig, data: TrainData, out_dir: str | Path, train_config: TrainConfig = TrainConfig(),
          val: EvalData | None = None, resume: bool = True, data_manifest_sha256: str | None = None,
          progress: bool = True, on_eval: Callable[[int, dict[str, float]], None] | None = None) -> TrainResult:
    """Train a detector; checkpoints ``out_dir/last`` (+ ``last.state.pt`` for resuming) and ``out_dir/best``.

    ``val``: held-out data for keep-best (image AUROC, then pixel AUROC); None uses a fixed synthetic-anomaly set
    built from the first training samples, which is weaker evidence: pass rendered defects when there are some.
    ``resume``: continue from ``out_dir/last`` when it exists (same model config required)."""
    from tqdm import tqdm

    tc = train_config
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    device = resolve_device(tc.device)
    precision = resolve_precision(tc.precision, device)
    channels_last = True if tc.channels_last is None else tc.channels_last
    if len(data) == 0:
        raise ModelError("no training samples")
    if val is None:
        val = synthetic_eval_data(data, config.priors, seed=tc.seed + 1)

    state_file = out / "last.state.pt"
    start_step, best, history = 0, None, []
    if resume and state_file.is_file():
        ck = load_checkpoint(out / "last", map_location=device)
        if ck.detector.config != config:
            raise CheckpointError(f"{paths(out / 'last')[1]}: resuming a different model ({ck.meta['model']}); "
                                  f"use another output folder or resume=False")
        detector = ck.detector.to(device)
        st = torch.load(state_file, map_location="cpu", weights_only=True)
    else:
        n_fit = min(len(data), 256)
        x_fit, _ = data.get(torch.arange(n_fit))
        detector = Detector(config, Normalizer.fit(x_fit))  # all pixels: background is input too
        detector.init_weights(torch.Generator().manual_seed(tc.seed))
        detector.to(device)
        st = None
    if channels_last:
        detector.to(memory_format=torch.channels_last)
    detector.train()
    optimizer = torch.optim.Adam(detector.parameters(), lr=tc.lr)
    milestones = [int(tc.steps * f) for f in tc.lr_milestones]
    scheduler = torch.optim.lr_scheduler.MultiStepLR(optimizer, milestones, gamma=tc.lr_gamma)
    index_gen = torch.Generator().manual_seed(tc.seed)
    synth_gen = torch.Generator(device=device).manual_seed(tc.seed + 7)
    if st is not None:
        optimizer.load_state_dict(st["optimizer"])
        scheduler.load_state_dict(st["scheduler"])
        index_gen.set_state(st["index_gen"])
        synth_gen.set_state(st["synth_gen"])
        start_step = int(st["step"])
        best = st.get("best") or None
        history = list(st.get("history", []))
        log.info("resuming %s at step %d of %d", out, start_step, tc.steps)

    def checkpoint(step: int, metrics: dict[str, float]) -> None:
        nonlocal best
        train_info = {"step": step, "train_config": _jsonable(asdict(tc)), "precision": precision,
                      "device": str(device)}
        if _better(metrics, best):
            best = dict(metrics)
            save_checkpoint(out / "best", detector, data_manifest_sha256=data_manifest_sha256, metrics=metrics,
                            train=train_info)
        save_checkpoint(out / "last", detector, data_manifest_sha256=data_manifest_sha256, metrics=metrics,
                        train=train_info)
        torch.save({"optimizer": optimizer.state_dict(), "scheduler": scheduler.state_dict(),
                    "index_gen": index_gen.get_state(), "synth_gen": synth_gen.get_state(), "step": step,
                    "best": best, "history": history}, state_file)

    t0 = time.perf_counter()
    deadline = t0 + tc.max_minutes * 60 if tc.max_minutes else math.inf
    bar = tqdm(total=tc.steps, initial=start_step, disable=not progress, unit="step", dynamic_ncols=True)
    step = start_step
    ema = None
    while step < tc.steps:
        idx = torch.randint(len(data), (tc.batch_size,), generator=index_gen)
        x, obj = data.get(idx)
        x, obj = x.to(device, non_blocking=True), obj.to(device, non_blocking=True)
        syn = synthesize(x, config.priors, synth_gen, tc.anomaly, obj)
        clean, aug = detector.normalize(x), detector.normalize(syn.augmented)
        if channels_last:
            clean = clean.contiguous(memory_format=torch.channels_last)
            aug = aug.contiguous(memory_format=torch.channels_last)
        with autocast(device, precision):
            total = torch.zeros((), device=device)
            terms = {}
            for name, net in detector.members.items():
                sl = detector.member_slice(name)
                o = net(aug[:, sl])
                assert isinstance(o, DraemTrainOutput)
                lt = draem_loss(clean[:, sl], o.reconstruction, o.logits, syn.mask)
                total = total + lt.total
                terms[name] = lt.as_floats()
        optimizer.zero_grad(set_to_none=True)
        total.backward()
        optimizer.step()
        scheduler.step()
        step += 1
        loss = float(total.detach())
        if not math.isfinite(loss):
            raise ModelError(f"training diverged at step {step}: loss {loss}")
        ema = loss if ema is None else 0.95 * ema + 0.05 * loss
        rate = (step - start_step) * tc.batch_size / max(time.perf_counter() - t0, 1e-9)
        bar.set_postfix(loss=f"{ema:.4f}", samples_s=f"{rate:.1f}", lr=f"{scheduler.get_last_lr()[0]:.1e}")
        bar.update(1)
        history.append({"step": step, "loss": loss, **{f"{k}_{t}": v for k, d in terms.items() for t, v in d.items()}})
        stop = time.perf_counter() > deadline
        if step % tc.eval_every == 0 or step == tc.steps or stop:
            metrics = evaluate(detector, val, tc.eval_batch_size, device, precision, channels_last).metrics
            history.append({"step": step, "eval": metrics})
            bar.write(f"step {step}: image AUROC {metrics['image_auroc']:.4f}, pixel AUROC "
                      f"{metrics['pixel_auroc']:.4f}, AUPRO {metrics['aupro_0.3']:.4f} ({val.kind} anomalies)")
            checkpoint(step, metrics)
            if on_eval:
                on_eval(step, metrics)
        if stop:
            log.info("stopping at step %d: max_minutes %.1f reached", step, tc.max_minutes)
            break
    bar.close()
    if step == start_step and not (out / "best.json").exists():  # nothing to do but nothing saved yet
        checkpoint(step, evaluate(detector, val, tc.eval_batch_size, device, precision, channels_last).metrics)
    return TrainResult(paths(out / "best")[0], paths(out / "last")[0], best or {}, history, step,
                       time.perf_counter() - t0)


def _jsonable(d: Any) -> Any:
    if isinstance(d, dict):
        return {k: _jsonable(v) for k, v in d.items()}
    if isinstance(d, (list, tuple)):
        return [_jsonable(v) for v in d]
    return d
