"""The frame around the model's view, as ``station eval`` and threshold setting read it (``station.datasets``,
``station.evaluation.model_split``): the view at its centre, NaN beyond the frame, only for a variation model."""

from __future__ import annotations

from pathlib import Path

import torch
from line_sets import make_line_set  # same folder (pytest puts it on sys.path)

from model.draem.roi import AROUND_PX, around_px_of
from station.datasets import concat, load_split


def test_a_split_comes_with_the_frame_around_each_view(tmp_path: Path) -> None:
    """A 64 x 96 frame's band (rows 16-47, columns 16-79) at 16 x 32 (2 frame px per input px): 4 input px around
    are 8 frame px, inside the frame; 16 are 32, beyond its top and bottom rows (NaN)."""
    data = make_line_set(tmp_path / "s", 6)
    sp = load_split(data, "train", ("intensity", "dolp"), (16, 32), progress=False, roi="band", around_px=4)
    n = len(sp.index)
    assert sp.around.shape == (n, 2, 24, 40) and torch.isfinite(sp.around).all()
    assert torch.allclose(sp.around[..., 5:-5, 5:-5], sp.priors[..., 1:-1, 1:-1], atol=1e-5)  # the view's pixels
    far = load_split(data, "train", ("intensity", "dolp"), (16, 32), progress=False, roi="band", around_px=16)
    assert torch.isnan(far.around[:, :, 0]).all() and torch.isfinite(far.around[..., 16:-16, 16:-16]).all()
    none = load_split(data, "train", ("intensity", "dolp"), (16, 32), progress=False, roi="band")
    assert none.around is None
    assert concat([sp, sp]).around.shape[0] == 2 * n and concat([sp, none]).around is None  # only when every set has


def test_only_a_variation_models_registration_reads_the_frame_around() -> None:
    assert around_px_of("band", ("intensity",), True) == AROUND_PX
    assert around_px_of("band", ("intensity",), False) == 0
    assert around_px_of("center", ("intensity", "normal"), True) == 0  # the estimator reads the centre square
    assert around_px_of("object", ("intensity",), True) == 0


def test_the_frame_around_is_the_model_files_setting() -> None:
    """``ModelConfig.around_px``: 0 (the view alone, every file before it) leaves the sidecar as it was; a variation
    model may read up to 64; a model without one, or reading the normal prior, may not (one line naming the key)."""
    import pytest

    from model.draem.config import ModelConfig
    from model.draem.errors import ModelError

    base = ModelConfig.from_preset("tiny", ("intensity",), "fused", 32, "band")
    assert "around_px" not in base.to_dict()
    reads = base.with_(variation=True, around_px=AROUND_PX)
    assert ModelConfig.from_dict(reads.to_dict()) == reads and reads.to_dict()["around_px"] == AROUND_PX
    for bad in (base.to_dict() | {"around_px": 16}, reads.to_dict() | {"around_px": 65},
                reads.to_dict() | {"around_px": -1}, reads.to_dict() | {"around_px": 1.5}):
        with pytest.raises(ModelError, match="around_px must be"):
            ModelConfig.from_dict(bad)
