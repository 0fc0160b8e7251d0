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


def test_eval_reports_the_cost_of_each_rule() -> None:
    from types import SimpleNamespace

    from station.commands.eval import early_exit_rows

    rng = np.random.default_rng(0)
    label = rng.random(200) < 0.3
    base = np.where(label, 0.7, 0.3)
    members = ("intensity", "aolp", "dolp")
    ev = SimpleNamespace(member_scores={m: np.clip(base + rng.normal(0, 0.2, 200), 0, 1) for m in members})
    rows = early_exit_rows(ev, label, 0.5, members)
    assert [r["early_exit"] for r in rows] == ["off", "exact", "margin 0.05", "margin 0.1", "margin 0.2"]
    assert rows[0]["members_per_part"] == 3 and rows[0]["decisions_changed"] == 0
    assert rows[1]["decisions_changed"] == 0 and rows[1]["members_per_part"] < 3
    # a smaller margin stops sooner (the running mean is more often that far from the threshold); exact runs most
    used = [r["members_per_part"] for r in rows[1:]]
    assert used[0] >= max(used[1:]) and used[1] <= used[2] <= used[3]
    assert rows[2]["decisions_changed"] >= rows[4]["decisions_changed"]
