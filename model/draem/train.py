"""Training DRAEM detectors on in-memory or streamed prior tensors, with held-out evaluation and keep-best.

Recipe as published: Adam (lr 1e-4), learning rate x0.2 at 80 % and 90 % of the steps, loss L2 + SSIM + focal
(``loss.py``), synthetic anomalies on half the samples (``anomaly.py``). Mixed supervision (ours, ``mixed.py``):
with ``rendered_fraction`` > 0 that share of every batch is rendered defective parts with their true masks, the rest
stays DRAEM's; at 0 (the default) the loop runs exactly as before. The ensemble (one DRAEM per prior) trains
all members in one loop on the same batches and the same synthetic masks; members share no parameters, so one Adam
over all of them is the same as one Adam each. Every ``eval_every`` steps the detector is evaluated on held-out
data (``evaluate.py``) and checkpointed; the best image AUROC is kept (it swings over training:
docs/platform-facts.md), the last is kept for resuming. Data loading is the caller's: this module never reads files
of the renderer. The step loop is ``_run_steps``; ``_restore_or_init``, ``_Streams`` (the random streams),
``_Checkpointer`` and ``_Learner`` (one optimiser step) are its parts.

Scale-out: launched by ``torchrun`` (``distributed.py``), every process runs this loop on its own device with its own
batches (``batch_size`` is per process: the global batch is ``batch_size x world size``, the learning rate is not
scaled) and its own synthetic anomalies (seeds shifted by ``distributed.rank_seed``); DistributedDataParallel
averages the gradients, so the weights stay identical on every rank. BatchNorm statistics are per process (no
SyncBatchNorm); DDP copies rank 0's running statistics to the others at every forward. Rank 0 alone reads and
writes checkpoints, evaluates, logs and shows progress; the others wait at a barrier. A single process is the
default and runs exactly as before (same seeds, same results, same files).
"""

from __future__ import annotations

import logging
import math
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Protocol

import torch
from torch import nn

from . import distributed, runtime
from . import evaluate as evaluation
from .anomaly import AnomalyConfig
from .checkpoint import load_checkpoint, paths, save_checkpoint
from .config import ModelConfig
from .detector import Detector
from .errors import CheckpointError, ConfigError, ModelError
from .loss import draem_loss
from .mixed import DefectData, TrainBatch, draw_batch, n_rendered
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


@dataclass(frozen=True)
class TrainConfig:
    """steps: optimiser steps; eval_every: steps between evaluation + checkpoint; precision: "fp32", "bf16"
    (autocast) or "auto" (fp32 on CPU: bf16 autocast was measured slower on this AVX2-only CPU, see docs/model.md;
    bf16 on CUDA); channels_last: None = on. ``max_minutes`` stops early (after a final checkpoint).
    ``stop_at_step``: stop after this step of the ``steps``-step schedule (after a checkpoint); a rerun with a later
    one, or none, resumes the same schedule (a long run split over sessions, or a base to fine-tune from).
    ``rendered_fraction``: share of each batch replaced by rendered defective samples (``train(defects=...)``,
    ``mixed.py``), rounded half up to a whole number of samples (``n_rendered``) that must leave at least one
    synthetic sample; 0 = DRAEM's synthetic anomalies only, exactly as before. ``polarization_noise``: largest
    Stokes noise (in units of S0) added to the inputs, a random level per sample (``polarization_noise.py``; 0 =
    none, exactly as before)."""

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
    stop_at_step: int | None = None
    anomaly: AnomalyConfig = field(default_factory=AnomalyConfig)
    rendered_fraction: float = 0.0
    polarization_noise: float = 0.0

    def __post_init__(self) -> None:
        for key in ("steps", "batch_size", "eval_every"):
            if getattr(self, key) < 1:
                raise ConfigError(key, f"{key} must be >= 1, got {getattr(self, key)}")
        if self.stop_at_step is not None and not 1 <= self.stop_at_step <= self.steps:
            raise ConfigError("stop_at_step",
                              f"stop_at_step must be in [1, steps = {self.steps}], got {self.stop_at_step}")
        if self.precision not in runtime.TRAIN_PRECISIONS:
            raise ConfigError("precision", f"precision must be auto, fp32 or bf16, got {self.precision!r}")
        if not 0.0 <= self.polarization_noise <= 1.0:
            raise ConfigError("polarization_noise",
                              f"polarization_noise must be in [0, 1] (units of S0), got {self.polarization_noise}")
        try:
            n_rendered(self.rendered_fraction, self.batch_size)  # a fraction the batch cannot hold
        except ModelError as exc:
            raise ConfigError("rendered_fraction", str(exc)) from None

    @property
    def n_rendered(self) -> int:
        """Rendered defective samples per batch (per process under torchrun)."""
        return n_rendered(self.rendered_fraction, self.batch_size)


@dataclass
class TrainResult:
    """Paths name rank 0's files under ``out_dir``. ``is_main``: this process is rank 0 (always True for a single
    process); the other ranks evaluated and wrote nothing, and their caller should stop there. ``history``: the
    losses are the mean over ranks; evaluations are recorded on rank 0 only. ``detector``: the plain module as the
    loop left it (last step's weights, identical on every rank; not the best)."""

    best_path: Path
    last_path: Path
    best_metrics: dict[str, float]
    history: list[dict[str, Any]]
    steps_done: int
    seconds: float
    is_main: bool = True
    world_size: int = 1
    detector: Detector | None = field(default=None, repr=False)


def _better(new: dict[str, float], old: dict[str, float] | None) -> bool:
    if old is None:
        return True
    key = lambda m: tuple(-math.inf if math.isnan(m.get(k, math.nan)) else m[k]  # noqa: E731
                          for k in ("image_auroc", "pixel_auroc"))
    return key(new) > key(old)


class _MemberForward(nn.Module):
    """Training forward of every member on its channels of the stacked input: ``{member: DraemTrainOutput}`` in
    the detector's member order. One module over all members, so one DDP wraps the whole detector's weights."""

    def __init__(self, detector: Detector):
        super().__init__()
        self.members = detector.members
        self._slices = {name: detector.member_slice(name) for name in detector.members}

    def forward(self, x: torch.Tensor) -> dict[str, DraemTrainOutput]:
        outs = {}
        for name, net in self.members.items():
            o = net(x[:, self._slices[name]])
            assert isinstance(o, DraemTrainOutput)
            outs[name] = o
        return outs


def train(config: ModelConfig, data: TrainData, out_dir: str | Path, train_config: TrainConfig = TrainConfig(),
          val: evaluation.EvalData | None = None, resume: bool = True, data_manifest_sha256: str | None = None,
          progress: bool = True, on_eval: Callable[[int, dict[str, float]], None] | None = None,
          train_meta: dict[str, Any] | None = None, defects: DefectData | None = None,
          init: str | Path | None = None) -> TrainResult:
    """Train a detector; checkpoints ``out_dir/last`` (+ ``last.state.pt`` for resuming) and ``out_dir/best``.

    ``val``: held-out data for keep-best (image AUROC, then pixel AUROC); None uses a fixed synthetic-anomaly set
    built from the first training samples, which is weaker evidence: pass rendered defects when there are some.
    ``resume``: continue from ``out_dir/last`` when it exists (same model config required). ``train_meta``: extra
    records for every checkpoint's ``train`` section (e.g. how the normal prior was made). ``defects``: rendered
    defective training samples with their masks (``mixed.DefectData``), used when ``train_config.rendered_fraction``
    > 0 (required then); their own index stream is seeded from ``seed + 13`` and checkpointed for resuming.
    ``init``: start from this checkpoint's weights and input normalisation (same model config required; a fresh
    optimiser and schedule), e.g. to fine-tune a model trained on good parts with rendered defects; a run that
    resumes from ``out_dir/last`` ignores it.

    Under ``torchrun`` (``WORLD_SIZE`` > 1) this runs data-parallel (module docstring): the process group is joined
    here unless the caller already did (``distributed.init``; it stays until the process exits); every rank passes
    the same ``data``; ``val``, ``out_dir``, ``progress`` and ``on_eval`` matter on rank 0 only, which reads and
    writes ``out_dir`` (the others need no access to it). Check ``TrainResult.is_main`` before using the files."""
    info = distributed.current()
    device = distributed.device_for(info, runtime.resolve_device(train_config.device))
    distributed.init(info, device)
    return _train(config, data, Path(out_dir), train_config, info, device, val=val, resume=resume,
                  data_manifest_sha256=data_manifest_sha256, progress=progress, on_eval=on_eval,
                  train_meta=train_meta or {}, defects=defects, init=init)


def _train(config: ModelConfig, data: TrainData, out: Path, tc: TrainConfig, info: distributed.DistInfo,
           device: torch.device, *, val: evaluation.EvalData | None, resume: bool, data_manifest_sha256: str | None,
           progress: bool, on_eval: Callable[[int, dict[str, float]], None] | None, train_meta: dict[str, Any],
           defects: DefectData | None, init: str | Path | None) -> TrainResult:
    """``train`` on this rank's ``device``: check the data, restore or initialise the detector, run the steps."""
    main = info.is_main
    if main:
        out.mkdir(parents=True, exist_ok=True)
    precision = runtime.resolve_precision(tc.precision, device)
    channels_last = True if tc.channels_last is None else tc.channels_last
    val = _check_data(config, data, tc, val, defects, main)
    detector, state = _restore_or_init(config, data, out, resume, init, tc.seed, info, device)
    if channels_last:
        detector.to(memory_format=torch.channels_last)
    detector.train()
    forward: nn.Module = _MemberForward(detector)
    if info.enabled:  # broadcasts rank 0's weights and buffers now, averages gradients in backward
        from torch.nn.parallel import DistributedDataParallel

        forward = DistributedDataParallel(forward, device_ids=[device.index] if device.type == "cuda" else None)
    optimizer = torch.optim.Adam(detector.parameters(), lr=tc.lr)
    milestones = [int(tc.steps * f) for f in tc.lr_milestones]
    scheduler = torch.optim.lr_scheduler.MultiStepLR(optimizer, milestones, gamma=tc.lr_gamma)
    saver = _Checkpointer(out, detector, optimizer, scheduler, _Streams.seeded(tc.seed, info.rank, device), info,
                          data_manifest_sha256, train_meta,
                          {"train_config": _jsonable(asdict(tc)), "precision": precision, "device": str(device)})
    start_step = 0
    if state is not None:
        start_step = saver.resume(state)
        if main:
            log.info("resuming %s at step %d of %d", out, start_step, tc.steps)
    t0 = time.perf_counter()
    learner = _Learner(detector, forward, optimizer, scheduler, device, precision, channels_last)
    steps_done = _run_steps(learner, saver, data, config.priors, tc, defects=defects, val=val, start_step=start_step,
                            t0=t0, progress=progress, on_eval=on_eval)
    best = distributed.broadcast_object(info, saver.best) if info.enabled else saver.best
    return TrainResult(paths(out / "best")[0], paths(out / "last")[0], best or {}, saver.history, steps_done,
                       time.perf_counter() - t0, main, info.world_size, detector)


def _check_data(config: ModelConfig, data: TrainData, tc: TrainConfig, val: evaluation.EvalData | None,
                defects: DefectData | None, main: bool) -> evaluation.EvalData | None:
    """ModelError without training samples, or without the rendered defects ``rendered_fraction`` asks for; the
    held-out data (on rank 0 a synthetic-anomaly set when none is given; the other ranks evaluate nothing)."""
    if len(data) == 0:
        raise ModelError("no training samples")
    rendered = tc.n_rendered
    if rendered and (defects is None or len(defects) == 0):
        raise ModelError(f"rendered_fraction {tc.rendered_fraction}: no rendered defective samples given")
    if defects is not None and not rendered and main:
        log.warning("%d rendered defective samples given but rendered_fraction is 0: not used", len(defects))
    if val is None and main:
        val = evaluation.synthetic_eval_data(data, config.priors, seed=tc.seed + 1)
    return val


def _attempt(info: distributed.DistInfo, load: Callable[[], Any]) -> tuple[Any, Exception | None]:
    """(``load()``, None); under torchrun an exception is returned instead of raised, so rank 0 can tell every rank
    (or the others would wait forever at the broadcast)."""
    try:
        return load(), None
    except Exception as exc:
        if not info.enabled:
            raise
        return None, exc


def _load_last(out: Path, config: ModelConfig, device: torch.device) -> tuple[Detector, dict[str, Any]]:
    """The detector of ``out/last`` and the loop state of ``out/last.state.pt`` (same model config required)."""
    ck = load_checkpoint(out / "last", map_location=device)
    if ck.detector.config != config:
        raise CheckpointError(f"{paths(out / 'last')[1]}: resuming a different model ({ck.meta['model']}); "
                              f"use another output folder or resume=False")
    state_path = out / "last.state.pt"
    try:
        state = torch.load(state_path, map_location="cpu", weights_only=True)
    except Exception as exc:  # torch raises several types for a damaged file
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
        raise CheckpointError(f"{state_path}: cannot resume from it ({type(exc).__name__}: {first}); delete it and "
                              "last.* to start over") from None
    if not isinstance(state, dict):
        raise CheckpointError(f"{state_path}: not a training state; delete it and last.* to start over")
    return ck.detector.to(device), state


def _load_init(init: str | Path, config: ModelConfig, device: torch.device) -> Detector:
    """The weights and normalisation of checkpoint ``init`` to start from (same model config required, except the
    region of interest, the input size and the frames' shape: the networks are convolutional, so a model trained on
    the centre square at 128 px can start one that sees the band at 96 x 192)."""
    ck = load_checkpoint(init, map_location=device)
    if ck.detector.config.with_(roi=config.roi, input_size_px=config.input_size_px,
                                frame_aspect=config.frame_aspect) != config:
        raise CheckpointError(f"{paths(init)[1]}: init from a different model ({ck.meta['model']}); it "
                              f"must have the trained model's priors, fusion and preset")
    log.info("starting from %s (step %s, roi %s)", paths(init)[0], (ck.meta.get("train") or {}).get("step"),
             ck.detector.config.roi)
    detector = ck.detector
    if detector.config != config:
        detector = Detector(config, ck.detector.normalizer)
        detector.load_state_dict(ck.detector.state_dict())
    return detector.to(device)


def _restore_or_init(config: ModelConfig, data: TrainData, out: Path, resume: bool, init: str | Path | None,
                     seed: int, info: distributed.DistInfo, device: torch.device
                     ) -> tuple[Detector, dict[str, Any] | None]:
    """The detector to train on ``device`` and the loop state to resume (None: a fresh start). Rank 0 resumes from
    ``out/last`` (``resume`` and its state file exists), else starts from ``init``, else fits the input
    normalisation on up to 256 training samples and initialises the weights from ``seed``. Under torchrun rank 0's
    outcome (state, normalisation, or its error) reaches every rank; its weights follow with DDP."""
    detector, state, normalizer, failure = None, None, None, None
    if info.is_main and resume and (out / "last.state.pt").is_file():
        loaded, failure = _attempt(info, lambda: _load_last(out, config, device))
        detector, state = loaded if loaded is not None else (None, None)
    if info.is_main and detector is None and failure is None and init is not None:
        detector, failure = _attempt(info, lambda: _load_init(init, config, device))
    if info.is_main and detector is None and failure is None:
        x_fit, _ = data.get(torch.arange(min(len(data), 256)))
        normalizer = Normalizer.fit(x_fit)  # all pixels: background is input too
    if info.enabled:  # rank 0's resume state and normalizer on every rank; its weights come with DDP
        shared = distributed.broadcast_object(info, {
            "error": None if failure is None else f"{type(failure).__name__}: {failure}",
            "normalizer": normalizer if detector is None else detector.normalizer,
            "state": state} if info.is_main else None)
        if failure is not None:
            raise failure
        if shared["error"]:
            raise ModelError(f"rank 0 could not resume from {out}: {shared['error']}")
        normalizer, state = shared["normalizer"], shared["state"]
    if detector is None:
        detector = Detector(config, normalizer)
        detector.init_weights(torch.Generator().manual_seed(seed))
        detector.to(device)
    return detector, state


@dataclass
class _Streams:
    """This rank's random streams: batch indices, DRAEM's synthetic anomalies (on the training device), rendered
    defects. Seeded from ``seed``, ``seed + 7``, ``seed + 13`` shifted per rank (``distributed.rank_seed``)."""

    index: torch.Generator
    synth: torch.Generator
    defect: torch.Generator

    @classmethod
    def seeded(cls, seed: int, rank: int, device: torch.device) -> _Streams:
        return cls(torch.Generator().manual_seed(distributed.rank_seed(seed, rank)),
                   torch.Generator(device=device).manual_seed(distributed.rank_seed(seed + 7, rank)),
                   torch.Generator().manual_seed(distributed.rank_seed(seed + 13, rank)))

    def states(self) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        return self.index.get_state(), self.synth.get_state(), self.defect.get_state()

    def restore(self, state: dict[str, Any], info: distributed.DistInfo, state_file: Path) -> None:
        """Continue the streams saved in ``state``: per rank when it was saved by as many processes; else rank 0
        takes the single-process streams and the other ranks keep their fresh seeds (said once)."""
        gens = state.get("rank_generators")
        if gens is not None and len(gens) == info.world_size:
            self.index.set_state(gens[info.rank][0])
            self.synth.set_state(gens[info.rank][1])
            if len(gens[info.rank]) > 2:  # saved before mixed supervision: (index, synth) only
                self.defect.set_state(gens[info.rank][2])
        elif info.rank == 0:
            self.index.set_state(state["index_gen"])
            self.synth.set_state(state["synth_gen"])
            if "defect_gen" in state:
                self.defect.set_state(state["defect_gen"])
        if (len(gens) if gens is not None else 1) != info.world_size and info.is_main:
            log.warning("%s was saved by %d process(es), resuming with %d: ranks > 0 restart their random streams",
                        state_file, len(gens) if gens is not None else 1, info.world_size)

    def gather(self, info: distributed.DistInfo) -> list[Any] | None:
        """Every rank's stream states on rank 0 (a collective: all ranks call it); None for a single process."""
        if not info.enabled:
            return None
        return distributed.all_gather_object(info, self.states())


@dataclass
class _Checkpointer:
    """Rank 0's files under ``out``: ``best`` (when ``_better`` than the best so far), ``last`` and
    ``last.state.pt`` (optimiser, schedule, random streams, step, best metrics, history) to resume from.
    Checkpoints record ``train_meta``, the step and ``run_info`` (train config, precision, device) as ``train``."""

    out: Path
    detector: Detector
    optimizer: torch.optim.Optimizer
    scheduler: torch.optim.lr_scheduler.LRScheduler
    streams: _Streams
    info: distributed.DistInfo
    data_manifest_sha256: str | None
    train_meta: dict[str, Any]
    run_info: dict[str, Any]
    best: dict[str, float] | None = None
    history: list[dict[str, Any]] = field(default_factory=list)

    @property
    def state_file(self) -> Path:
        return self.out / "last.state.pt"

    def resume(self, state: dict[str, Any]) -> int:
        """Take up ``state`` (from ``last.state.pt``): optimiser, schedule, streams, best, history; its step."""
        self.optimizer.load_state_dict(state["optimizer"])
        self.scheduler.load_state_dict(state["scheduler"])
        self.streams.restore(state, self.info, self.state_file)
        self.best = state.get("best") or None
        self.history = list(state.get("history", []))
        return int(state["step"])

    def save(self, step: int, metrics: dict[str, float], generators: list[Any] | None) -> None:
        """Write ``last`` (and ``best`` when better) with ``metrics`` and the loop state at ``step``;
        ``generators``: every rank's stream states under torchrun (``_Streams.gather``), None for one process."""
        train_info = {**self.train_meta, "step": step, **self.run_info}
        if _better(metrics, self.best):
            self.best = dict(metrics)
            save_checkpoint(self.out / "best", self.detector, data_manifest_sha256=self.data_manifest_sha256,
                            metrics=metrics, train=train_info)
        save_checkpoint(self.out / "last", self.detector, data_manifest_sha256=self.data_manifest_sha256,
                        metrics=metrics, train=train_info)
        index, synth, defect = self.streams.states()
        state = {"optimizer": self.optimizer.state_dict(), "scheduler": self.scheduler.state_dict(),
                 "index_gen": index, "synth_gen": synth, "defect_gen": defect, "step": step, "best": self.best,
                 "history": self.history}
        if generators is not None:  # distributed: (index, synth, defect) generator states per rank
            state["rank_generators"] = generators
        torch.save(state, self.state_file)


@dataclass
class _Learner:
    """What one optimiser step and an evaluation need: the detector, its member forward (DDP-wrapped under
    torchrun), optimiser, schedule, device, precision and memory format."""

    detector: Detector
    forward: nn.Module
    optimizer: torch.optim.Optimizer
    scheduler: torch.optim.lr_scheduler.LRScheduler
    device: torch.device
    precision: runtime.Precision
    channels_last: bool

    def step(self, batch: TrainBatch) -> tuple[float, dict[str, dict[str, float]]]:
        """One optimiser step on ``batch``: (total loss over the members, each member's loss terms)."""
        clean, aug = self.detector.normalize(batch.target), self.detector.normalize(batch.inputs)
        if self.channels_last:
            clean = clean.contiguous(memory_format=torch.channels_last)
            aug = aug.contiguous(memory_format=torch.channels_last)
        with runtime.autocast(self.device, self.precision):
            total = torch.zeros((), device=self.device)
            terms = {}
            for name, o in self.forward(aug).items():
                sl = self.detector.member_slice(name)
                lt = draem_loss(clean[:, sl], o.reconstruction, o.logits, batch.mask, batch.recon_weight)
                total = total + lt.total
                terms[name] = lt.as_floats()
        self.optimizer.zero_grad(set_to_none=True)
        total.backward()
        self.optimizer.step()
        self.scheduler.step()
        return float(total.detach()), terms

    def evaluate(self, val: evaluation.EvalData, batch_size: int) -> dict[str, float]:
        return evaluation.evaluate(self.detector, val, batch_size, self.device, self.precision,
                                   self.channels_last).metrics


def _run_steps(learner: _Learner, saver: _Checkpointer, data: TrainData, priors: tuple[str, ...], tc: TrainConfig, *,
               defects: DefectData | None, val: evaluation.EvalData | None, start_step: int, t0: float,
               progress: bool, on_eval: Callable[[int, dict[str, float]], None] | None) -> int:
    """The step loop from ``start_step`` (``t0``: its start, ``time.perf_counter()``) to ``tc.steps`` or
    ``tc.max_minutes``: draw, step, agree across ranks, and every ``eval_every`` steps (and at the end) evaluate
    and checkpoint on rank 0. Returns the steps done."""
    from tqdm import tqdm

    info, main, streams = saver.info, saver.info.is_main, saver.streams
    deadline = t0 + tc.max_minutes * 60 if tc.max_minutes else math.inf
    bar = tqdm(total=tc.steps, initial=start_step, disable=not (progress and main), unit="step", dynamic_ncols=True)
    step = start_step
    ema = None
    end = tc.stop_at_step or tc.steps
    while step < end:
        batch = draw_batch(data, priors, tc.batch_size, streams.index, streams.synth, tc.anomaly, learner.device,
                           defects, tc.n_rendered, streams.defect, tc.polarization_noise)
        loss, terms = learner.step(batch)
        step += 1
        stop = time.perf_counter() > deadline
        diverged = not math.isfinite(loss)
        if info.enabled:  # all ranks decide alike, or one waits forever for the others
            loss, terms, diverged, stop = _agree(info, learner.device, loss, terms, stop)
        if diverged:
            raise ModelError(f"training diverged at step {step}: loss {loss}"
                             + (f" (mean over {info.world_size} ranks)" if info.enabled else ""))
        ema = loss if ema is None else 0.95 * ema + 0.05 * loss
        rate = (step - start_step) * tc.batch_size * info.world_size / max(time.perf_counter() - t0, 1e-9)
        bar.set_postfix(loss=f"{ema:.4f}", samples_s=f"{rate:.1f}", lr=f"{learner.scheduler.get_last_lr()[0]:.1e}")
        bar.update(1)
        saver.history.append({"step": step, "loss": loss,
                              **{f"{k}_{t}": v for k, d in terms.items() for t, v in d.items()}})
        if step % tc.eval_every == 0 or step == end or stop:
            gens = streams.gather(info)
            if main:
                assert val is not None
                metrics = learner.evaluate(val, tc.eval_batch_size)
                saver.history.append({"step": step, "eval": metrics})
                bar.write(f"step {step}: image AUROC {metrics['image_auroc']:.4f}, pixel AUROC "
                          f"{metrics['pixel_auroc']:.4f}, AUPRO {metrics['aupro_0.3']:.4f} ({val.kind} anomalies)")
                saver.save(step, metrics, gens)
                if on_eval:
                    on_eval(step, metrics)
            distributed.barrier(info)
        if stop:
            if main:
                log.info("stopping at step %d: max_minutes %.1f reached", step, tc.max_minutes)
            break
    bar.close()
    if step == start_step:  # nothing to do, but maybe nothing saved yet
        gens = streams.gather(info)
        if main and not (saver.out / "best.json").exists():
            assert val is not None
            saver.save(step, learner.evaluate(val, tc.eval_batch_size), gens)
        distributed.barrier(info)
    return step


def _agree(info: distributed.DistInfo, device: torch.device, loss: float, terms: dict[str, dict[str, float]],
           stop: bool) -> tuple[float, dict[str, dict[str, float]], bool, bool]:
    """One all-reduce per step: loss and loss terms averaged over ranks, diverged (a non-finite loss on any rank)
    and stop (any rank past its deadline) true for all ranks alike."""
    keys = [(k, t) for k, d in terms.items() for t in d]
    sums = distributed.all_reduce_sum(info, [loss, *(terms[k][t] for k, t in keys), float(not math.isfinite(loss)),
                                             float(stop)], device)
    n = info.world_size
    mean_terms: dict[str, dict[str, float]] = {}
    for (k, t), v in zip(keys, sums[1:-2], strict=True):
        mean_terms.setdefault(k, {})[t] = v / n
    return sums[0] / n, mean_terms, sums[-2] > 0, sums[-1] > 0


def _jsonable(d: Any) -> Any:
    if isinstance(d, dict):
        return {k: _jsonable(v) for k, v in d.items()}
    if isinstance(d, (list, tuple)):
        return [_jsonable(v) for v in d]
    return d
