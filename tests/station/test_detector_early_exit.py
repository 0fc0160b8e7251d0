"""``DraemDetector`` with early exit: members stop as soon as the decision is settled, decisions unchanged."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import torch

from model.draem.checkpoint import save_checkpoint
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.priors.testing import detailed_stokes
from station.model_detector import DraemDetector, ModelLoadError


@pytest.fixture(scope="module")
def ensemble(tmp_path_factory) -> Path:
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "ensemble", 32))
    det.init_weights(torch.Generator().manual_seed(0))
    path = tmp_path_factory.mktemp("ens") / "best"
    save_checkpoint(path, det, threshold=0.5, threshold_rule="test")
    return path


def frames(n: int) -> list[dict[str, np.ndarray]]:
    rng = np.random.default_rng(0)
    s0, s1, s2 = detailed_stokes(64, 64)
    out = []
    for _ in range(n):
        noise = rng.normal(0, 0.05, s0.shape).astype(np.float32)
        a = 0.5 * np.arctan2(s2, s1)
        out.append({"intensity": np.clip(s0 / 2 + noise, 0, 1), "dolp": np.clip(np.hypot(s1, s2) / s0, 0, 1),
                    "aolp_cos": np.cos(2 * a), "aolp_sin": np.sin(2 * a)})
    return out


def test_exact_early_exit_keeps_decisions_and_can_skip_members(ensemble: Path) -> None:
    maps = frames(4)
    full = DraemDetector(ensemble, "cpu")
    scores = [full.infer(m).score for m in maps]
    assert full.members_run == 4 * 3
    # put the threshold where the first member already settles every part: at 0 every part is a reject after one
    for thr, expect_runs in ((0.0, 4), (1.0, 4)):
        early = DraemDetector(ensemble, "cpu", threshold=thr, early_exit_margin=0.0)
        out = [early.infer(m).score for m in maps]
        assert early.members_run == expect_runs
        assert [s > thr for s in out] == [s > thr for s in scores]
    mid = float(np.median(scores))
    exact = DraemDetector(ensemble, "cpu", threshold=mid, early_exit_margin=0.0)
    assert [exact.infer(m).score > mid for m in maps] == [s > mid for s in scores]
    assert 4 <= exact.members_run <= 12


def test_early_exit_is_refused_out_of_range_and_ignored_for_one_network(ensemble: Path, tmp_path: Path) -> None:
    with pytest.raises(ModelLoadError, match="margin"):
        DraemDetector(ensemble, "cpu", early_exit_margin=2.0)
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp"), "fused", 32))
    save_checkpoint(tmp_path / "fused", det, threshold=0.5)
    assert DraemDetector(tmp_path / "fused", "cpu", early_exit_margin=0.1).early_exit_margin is None
