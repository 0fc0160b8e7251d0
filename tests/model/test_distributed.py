"""Scale-out of DRAEM training: ``distributed.from_env`` parsing, and a real two-process CPU run (torchrun, Gloo,
loopback only) of the ``tiny`` preset checked against the single-process path.

The two-process part runs this file as the worker script: ``torchrun ... test_distributed.py ROOT`` writes one
``worker<rank>.pt`` per rank under ROOT, which the test reads back.
"""

from __future__ import annotations

import dataclasses
import os
import signal
import socket
import subprocess
import sys
from pathlib import Path

import pytest
import torch

from model.draem import distributed
from model.draem.config import ModelConfig
from model.draem.errors import ModelError
from model.draem.mixed import TensorDefectData
from model.draem.train import TensorData, TrainConfig, train

PRIORS = ("intensity", "dolp")  # an ensemble of two tiny networks: one DDP over both members
REPO = Path(__file__).resolve().parents[2]


def test_from_env_parses_torchrun_variables():
    assert distributed.from_env({}) == distributed.DistInfo(0, 1, 0)
    assert not distributed.from_env({}).enabled and distributed.from_env({}).is_main
    info = distributed.from_env({"WORLD_SIZE": "4", "RANK": "3", "LOCAL_RANK": "1"})
    assert info == distributed.DistInfo(3, 4, 1) and info.enabled and not info.is_main
    assert distributed.from_env({"WORLD_SIZE": "2", "RANK": "1"}).local_rank == 1
    assert not distributed.from_env({"WORLD_SIZE": "1", "RANK": "0", "LOCAL_RANK": "0"}).enabled
    with pytest.raises(ModelError, match="RANK is not"):
        distributed.from_env({"WORLD_SIZE": "2"})
    with pytest.raises(ModelError, match="WORLD_SIZE='two'"):
        distributed.from_env({"WORLD_SIZE": "two", "RANK": "0"})
    with pytest.raises(ModelError, match="RANK=2"):
        distributed.from_env({"WORLD_SIZE": "2", "RANK": "2"})


def test_rank_seeds_and_devices():
    assert distributed.rank_seed(5, 0) == 5 and len({distributed.rank_seed(0, r) for r in range(8)}) == 8
    two = distributed.DistInfo(1, 2, 1)
    assert distributed.device_for(two, torch.device("cuda")) == torch.device("cuda", 1)
    assert distributed.device_for(distributed.SINGLE, torch.device("cuda", 2)) == torch.device("cuda", 2)
    assert distributed.device_for(two, torch.device("cpu")) == torch.device("cpu")
    assert distributed.backend_for(torch.device("cuda", 0)) == "nccl"
    assert distributed.backend_for(torch.device("cpu")) == "gloo"


def _data(nan_from_call: int | None = None) -> _RecordingData:
    g = torch.Generator().manual_seed(0)
    yy, xx = torch.meshgrid(torch.linspace(-1, 1, 32), torch.linspace(-1, 1, 32), indexing="ij")
    obj = ((yy**2 + xx**2) < 0.6).expand(8, 32, 32).clone()
    return _RecordingData(torch.rand(8, 2, 32, 32, generator=g), obj, nan_from_call)


class _RecordingData(TensorData):
    """TensorData that records the indices of every ``get`` (and returns NaN from call ``nan_from_call`` on)."""

    def __init__(self, priors: torch.Tensor, object_mask: torch.Tensor, nan_from_call: int | None = None):
        super().__init__(priors, object_mask)
        self.calls: list[list[int]] = []
        self.nan_from_call = nan_from_call

    def get(self, indices: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        self.calls.append(indices.tolist())
        x, obj = super().get(indices)
        if self.nan_from_call is not None and len(self.calls) >= self.nan_from_call:
            x = torch.full_like(x, float("nan"))
        return x, obj


def _defects() -> TensorDefectData:
    """Six 'rendered' defective samples: random priors with a square defect mask each."""
    x, obj = _data().priors[:6] + 0.3, _data().object_mask[:6]
    mask = torch.zeros(6, 32, 32, dtype=torch.bool)
    for i in range(6):
        mask[i, 8 + 2 * i:14 + 2 * i, 10:16] = True
    return TensorDefectData(x.clamp(0, 1), obj, mask)


def _cfg() -> ModelConfig:
    return ModelConfig.from_preset("tiny", PRIORS, "ensemble", input_size_px=32)


TC = {"batch_size": 2, "eval_every": 3, "seed": 3}


def _losses(history: list[dict]) -> list[float]:
    return [h["loss"] for h in history if "loss" in h]


def _worker(root: Path) -> None:
    """One rank of the two-process run (started by torchrun with this file as the script)."""
    torch.set_num_threads(1)
    info = distributed.from_env()
    rank = info.rank
    out: dict = {"info": info}
    # a: straight run; train() joins the process group from torchrun's environment (and keeps it for b and c)
    data = _data()
    res = train(_cfg(), data, root / "a" / f"rank{rank}", TrainConfig(steps=3, **TC), progress=False)
    out["a"] = {"is_main": res.is_main, "world_size": res.world_size, "steps": res.steps_done,
                "losses": _losses(res.history), "best": res.best_metrics, "calls": data.calls,
                "params": {k: v.detach().clone() for k, v in res.detector.named_parameters()}}
    out["a_joined_group"] = torch.distributed.is_initialized()
    # b: stopped after one step (max_minutes), then resumed to the same three steps
    b = root / "b" / f"rank{rank}"
    first = train(_cfg(), _data(), b, TrainConfig(steps=3, max_minutes=1e-9, **TC), progress=False)
    again = train(_cfg(), _data(), b, TrainConfig(steps=3, **TC), progress=False)
    out["b"] = {"first_steps": first.steps_done, "steps": again.steps_done, "losses": _losses(again.history),
                "params": {k: v.detach().clone() for k, v in again.detector.named_parameters()}}
    # c: a NaN loss on rank 1 only (its second batch): every rank must raise at the same step, none may hang
    try:
        train(_cfg(), _data(nan_from_call=2 if rank == 1 else None), root / "c" / f"rank{rank}",
              TrainConfig(steps=4, **TC), progress=False)
        out["c"] = "no error"
    except ModelError as exc:
        out["c"] = str(exc)
    # d: mixed supervision (half of each batch rendered defects), straight and stopped + resumed
    mixed = TrainConfig(steps=3, **{**TC, "rendered_fraction": 0.5})
    d = train(_cfg(), _data(), root / "d" / f"rank{rank}", mixed, progress=False, defects=_defects())
    e = root / "e" / f"rank{rank}"
    train(_cfg(), _data(), e, dataclasses.replace(mixed, max_minutes=1e-9), progress=False,
          defects=_defects())
    e_again = train(_cfg(), _data(), e, mixed, progress=False, defects=_defects())
    out["d"] = {"losses": _losses(d.history), "resumed": _losses(e_again.history),
                "params": {k: v.detach().clone() for k, v in d.detector.named_parameters()}}
    torch.save(out, root / f"worker{rank}.pt")


def _free_loopback_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_two_process_ddp_matches_ranks_and_single_process(tmp_path):
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(REPO), os.environ.get("PYTHONPATH", "")]),
           "OMP_NUM_THREADS": "1", "GLOO_SOCKET_IFNAME": "lo", "MASTER_ADDR": "127.0.0.1"}
    cmd = [sys.executable, "-m", "torch.distributed.run", "--nnodes=1", "--nproc_per_node=2",
           "--master_addr=127.0.0.1", f"--master_port={_free_loopback_port()}", __file__, str(tmp_path)]
    proc = subprocess.Popen(cmd, env=env, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            start_new_session=True)  # its own process group: a hang kills the workers too
    try:
        log, _ = proc.communicate(timeout=240)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        log, _ = proc.communicate()
        pytest.fail(f"two-process run hung (deadlock?):\n{log[-3000:]}")
    assert proc.returncode == 0, log[-3000:]
    w = [torch.load(tmp_path / f"worker{r}.pt", weights_only=False) for r in (0, 1)]

    # only rank 0 wrote checkpoints; rank 1 created nothing
    assert {p.name for p in (tmp_path / "a" / "rank0").iterdir()} >= {"best.pt", "best.json", "last.pt",
                                                                       "last.json", "last.state.pt"}
    assert not any((tmp_path / d / "rank1").exists() for d in "abc")
    state = torch.load(tmp_path / "a" / "rank0" / "last.state.pt", weights_only=True)
    assert len(state["rank_generators"]) == 2
    a0, a1 = w[0]["a"], w[1]["a"]
    assert (a0["is_main"], a1["is_main"], a0["world_size"], a0["steps"], a1["steps"]) == (True, False, 2, 3, 3)
    assert w[0]["a_joined_group"] and w[1]["a_joined_group"]
    assert a1["best"] == a0["best"] and "image_auroc" in a0["best"]  # keep-best broadcast from rank 0

    # each rank trained on its own batches (rank 1 also skips the validation set and the normaliser fit) ...
    batches0 = [c for c in a0["calls"] if len(c) == TC["batch_size"]]
    batches1 = a1["calls"]
    assert len(batches0) == len(batches1) == 3 and batches0 != batches1
    # ... yet DDP kept the weights identical: without averaged gradients they would differ
    assert a0["params"].keys() == a1["params"].keys()
    assert all(torch.equal(a0["params"][k], a1["params"][k]) for k in a0["params"])
    assert a0["losses"] == a1["losses"]  # mean over ranks

    # resume after a stop agreed by both ranks continues exactly, per-rank random streams included
    assert [w[r]["b"]["first_steps"] for r in (0, 1)] == [1, 1] and w[0]["b"]["steps"] == 3
    assert w[0]["b"]["losses"] == pytest.approx(a0["losses"], rel=1e-5)
    for k, v in a0["params"].items():
        torch.testing.assert_close(w[1]["b"]["params"][k], v, rtol=1e-4, atol=1e-6)

    # divergence on one rank: both raise at the same step (without agreement rank 0 would wait forever)
    assert all("training diverged at step 2" in w[r]["c"] for r in (0, 1)), (w[0]["c"], w[1]["c"])

    # mixed supervision under DDP: weights identical on both ranks, the defect streams checkpointed per rank
    d0, d1 = w[0]["d"], w[1]["d"]
    assert all(torch.equal(d0["params"][k], d1["params"][k]) for k in d0["params"])
    assert d0["resumed"] == pytest.approx(d0["losses"], rel=1e-5)
    gens = torch.load(tmp_path / "e" / "rank0" / "last.state.pt", weights_only=True)["rank_generators"]
    assert len(gens) == 2 and all(len(g) == 3 for g in gens)  # (index, synth, defect) per rank

    # the single-process path: rank 0's streams are the single process's, with no process group and no extra state
    torch.set_num_threads(1)  # as each worker; two threads on two shared cores run this 5x slower (conftest restores)
    single = _data()
    res = train(_cfg(), single, tmp_path / "single", TrainConfig(steps=3, **TC), progress=False)
    assert res.is_main and res.world_size == 1 and not torch.distributed.is_initialized()
    assert single.calls == a0["calls"]
    assert "rank_generators" not in torch.load(tmp_path / "single" / "last.state.pt", weights_only=True)
    assert _losses(res.history) != a0["losses"]  # the two-process loss averages in rank 1's batches


if __name__ == "__main__":
    _worker(Path(sys.argv[1]))
