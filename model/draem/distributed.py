"""Scale-out of DRAEM training over processes with ``torch.distributed`` (one process per GPU, ``torchrun``).

Conventions: a launch is distributed when the environment says so the way ``torchrun`` does (``WORLD_SIZE`` > 1,
``RANK``, ``LOCAL_RANK``); otherwise it is a single process and nothing here touches ``torch.distributed``.
Rank 0 is the main process: it alone reads and writes files, evaluates and logs. The backend is NCCL for CUDA
devices and Gloo otherwise; each process drives ``cuda:LOCAL_RANK``. Importing this module has no side effects.
"""

from __future__ import annotations

import atexit
import datetime
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, TypeVar

import torch
import torch.distributed as dist

from .errors import ModelError

T = TypeVar("T")

RANK_SEED_STRIDE = 1_000_003
"""Offset between the seeds of two ranks (``rank_seed``): a prime larger than any seed offset the trainer uses."""


@dataclass(frozen=True)
class DistInfo:
    """Where this process sits: global ``rank`` in [0, world_size), ``local_rank`` on its node (its GPU index)."""

    rank: int = 0
    world_size: int = 1
    local_rank: int = 0

    @property
    def enabled(self) -> bool:
        """True when more than one process trains (DDP, collectives); False for the single-process default."""
        return self.world_size > 1

    @property
    def is_main(self) -> bool:
        """True on rank 0, the process that evaluates, logs and writes checkpoints."""
        return self.rank == 0


SINGLE = DistInfo()


def from_env(env: Mapping[str, str] | None = None) -> DistInfo:
    """The ``DistInfo`` that ``torchrun`` announces in ``env`` (default ``os.environ``).

    No ``WORLD_SIZE`` means a single process. With it, ``RANK`` is required and ``LOCAL_RANK`` defaults to
    ``RANK``. Raises ``ModelError`` naming the variable when a value is not an integer or out of range."""
    env = os.environ if env is None else env
    if "WORLD_SIZE" not in env:
        return SINGLE

    def _int(name: str, default: int | None = None) -> int:
        raw = env.get(name)
        if raw is None:
            if default is None:
                raise ModelError(f"distributed launch: WORLD_SIZE is set but {name} is not (launch with torchrun)")
            return default
        try:
            return int(raw)
        except ValueError:
            raise ModelError(f"distributed launch: {name}={raw!r} is not an integer") from None

    world_size = _int("WORLD_SIZE")
    rank = _int("RANK")
    local_rank = _int("LOCAL_RANK", rank)
    if world_size < 1 or not 0 <= rank < world_size or local_rank < 0:
        raise ModelError(f"distributed launch: need WORLD_SIZE >= 1, 0 <= RANK < WORLD_SIZE, LOCAL_RANK >= 0; got "
                         f"WORLD_SIZE={world_size}, RANK={rank}, LOCAL_RANK={local_rank}")
    return DistInfo(rank, world_size, local_rank)


def current() -> DistInfo:
    """This process's place: from the initialised default process group if there is one, else ``from_env()``."""
    if dist.is_available() and dist.is_initialized():
        env = from_env()
        rank = dist.get_rank()
        return DistInfo(rank, dist.get_world_size(), env.local_rank if env.rank == rank else rank)
    return from_env()


def rank_seed(seed: int, rank: int) -> int:
    """The seed rank ``rank`` uses for a stream seeded ``seed``: ``seed + RANK_SEED_STRIDE * rank``; rank 0 keeps
    ``seed``, so a single process draws exactly what it drew before scale-out existed."""
    return seed + RANK_SEED_STRIDE * rank


def device_for(info: DistInfo, device: torch.device) -> torch.device:
    """The device this rank trains on: ``cuda:LOCAL_RANK`` when ``device`` is CUDA and training is distributed
    (an explicit CUDA index is replaced), ``device`` otherwise."""
    if info.enabled and device.type == "cuda":
        return torch.device("cuda", info.local_rank)
    return device


def backend_for(device: torch.device) -> str:
    """``"nccl"`` for CUDA devices, ``"gloo"`` for everything else."""
    return "nccl" if device.type == "cuda" else "gloo"


def init(info: DistInfo, device: torch.device, timeout_s: float | None = None) -> bool:
    """Join the default process group for ``info`` (env:// rendezvous: ``MASTER_ADDR``/``MASTER_PORT`` as set by
    torchrun) and leave it at interpreter exit. Returns True when this call created it; False when training is not
    distributed or a group already exists (it is reused: re-creating the default group in one process races with
    the previous group's rendezvous keys in torchrun's store, so a group lives as long as its process)."""
    if not info.enabled:
        return False
    if not dist.is_available():
        raise ModelError("distributed launch, but this torch build has no torch.distributed")
    if device.type == "cuda":
        torch.cuda.set_device(device)  # NCCL's object collectives use the current device
    if dist.is_initialized():
        return False
    kwargs: dict[str, Any] = {}
    if timeout_s is not None:
        kwargs["timeout"] = datetime.timedelta(seconds=timeout_s)
    dist.init_process_group(backend_for(device), rank=info.rank, world_size=info.world_size, **kwargs)
    atexit.register(shutdown)
    return True


def shutdown() -> None:
    """Leave and destroy the default process group (no-op when there is none)."""
    if dist.is_available() and dist.is_initialized():
        dist.destroy_process_group()


def barrier(info: DistInfo) -> None:
    """Wait for every rank (no-op for a single process)."""
    if info.enabled:
        dist.barrier()


def broadcast_object(info: DistInfo, obj: T | None, src: int = 0) -> T:
    """Rank ``src``'s picklable ``obj`` on every rank (returned unchanged for a single process)."""
    if not info.enabled:
        return obj  # type: ignore[return-value]
    box = [obj]
    dist.broadcast_object_list(box, src=src)
    return box[0]  # type: ignore[return-value]


def all_gather_object(info: DistInfo, obj: T) -> list[T]:
    """Every rank's picklable ``obj``, indexed by rank (``[obj]`` for a single process)."""
    if not info.enabled:
        return [obj]
    out: list[Any] = [None] * info.world_size
    dist.all_gather_object(out, obj)
    return out


def all_reduce_sum(info: DistInfo, values: Sequence[float], device: torch.device) -> list[float]:
    """Element-wise sum over ranks of ``values`` (float64 on ``device``: CUDA for NCCL); unchanged when single."""
    if not info.enabled:
        return list(values)
    t = torch.tensor(list(values), dtype=torch.float64, device=device)
    dist.all_reduce(t, op=dist.ReduceOp.SUM)
    return t.tolist()
