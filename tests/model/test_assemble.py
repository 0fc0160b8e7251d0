"""``model.draem.assemble``: an ensemble assembled from single-prior models scores as their average."""

from __future__ import annotations

import pytest
import torch

from model.draem.assemble import assemble_ensemble
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.draem.errors import ModelError
from model.draem.preprocess import Normalizer


def single(priors: tuple[str, ...], seed: int, mean: float, size: int = 32) -> Detector:
    cfg = ModelConfig.from_preset("tiny", priors, "fused", size)
    det = Detector(cfg, Normalizer((mean,) * cfg.in_channels, (2.0,) * cfg.in_channels))
    det.init_weights(torch.Generator().manual_seed(seed))
    return det.eval()


def test_assembled_members_score_as_the_models_they_came_from() -> None:
    r, a = single(("intensity",), 1, 0.2), single(("aolp",), 2, -0.5)
    ens = assemble_ensemble([r, a], ["r", "a"])
    assert ens.config.fusion == "ensemble" and ens.config.priors == ("intensity", "aolp")
    assert ens.normalizer.mean == (0.2, -0.5, -0.5)  # each member keeps its own normalisation
    x = torch.rand(2, 3, 32, 32, generator=torch.Generator().manual_seed(3))
    obj = torch.ones(2, 32, 32, dtype=torch.bool)
    out = ens.predict(x, obj)
    alone = {"intensity": r.predict(x[:, :1], obj).score, "aolp": a.predict(x[:, 1:], obj).score}
    for prior, score in alone.items():
        torch.testing.assert_close(out.member_scores[prior], score)
    torch.testing.assert_close(out.score, (alone["intensity"] + alone["aolp"]) / 2)


def test_members_that_cannot_share_an_ensemble_are_refused_by_name() -> None:
    r = single(("intensity",), 1, 0.0)
    with pytest.raises(ModelError, match=r"two: its network 'fused' reads 2 priors"):
        assemble_ensemble([r, single(("aolp", "dolp"), 2, 0.0)], ["one", "two"])
    with pytest.raises(ModelError, match=r"again: prior 'intensity' is already given by one"):
        assemble_ensemble([r, single(("intensity",), 2, 0.0)], ["one", "again"])
    with pytest.raises(ModelError, match=r"big: differs from one in input_size_px 64 vs 32"):
        assemble_ensemble([r, single(("dolp",), 2, 0.0, size=64)], ["one", "big"])
