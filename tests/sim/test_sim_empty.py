"""Empty samples: the same randomised scene without the part, chosen by index from the manifest alone, and sets
without them unchanged (manifest, pixels of the samples that show the part)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from sim import dataset as sd
from sim.errors import SimError

TINY = {"width": 64, "height": 48, "spp": 4}


def test_an_empty_sample_is_its_scene_without_the_part() -> None:
    with_empty = sd.DatasetSpec(seed=3, defect_fraction=1.0, empty_rate=0.5, **TINY)
    plain = sd.DatasetSpec(seed=3, defect_fraction=1.0, **TINY)
    assert sd.is_empty(3, 1, 0.5) and not sd.is_empty(3, 0, 0.5)
    model = sd.prepare(plain)
    empty, shown = sd.generate_sample(with_empty, model, 1), sd.generate_sample(plain, model, 1)
    assert empty.params["empty"] is True and "empty" not in shown.params
    assert empty.params["scene"] == shown.params["scene"]  # same camera, light, background
    assert empty.label == 0 and empty.params["defect"] is None  # test split wants a defect: not on an empty view
    assert not empty.object_mask.any() and not empty.defect_mask.any() and not empty.part_index.any()
    assert shown.object_mask.sum() > 50 and empty.raw.shape == shown.raw.shape
    assert empty.raw.mean() > 5  # the ground is lit
    # a sample that shows the part does not depend on empty_rate (its own random stream)
    np.testing.assert_array_equal(sd.generate_sample(with_empty, model, 0).raw, sd.generate_sample(plain, model, 0).raw)


def test_manifest_and_indices(tmp_path) -> None:
    assert "empty_rate" not in sd.DatasetSpec().to_dict()  # sets rendered before the key resume unchanged
    spec = sd.DatasetSpec(seed=3, empty_rate=0.5, width=8, height=8)
    manifest = sd.init_dataset(tmp_path / "ds", spec, 10)
    assert manifest["config"]["empty_rate"] == 0.5
    for i in range(10):
        empty = sd.is_empty(3, i, 0.5)
        params = {"index": i, "split": sd.split_of(i), "label": 0, "defect": None, **({"empty": True} if empty else {})}
        sd.write_sample(tmp_path / "ds", sd.Sample(i, np.zeros((8, 8), np.uint8), params, 0, sd.split_of(i)))
    ds = sd.Dataset(tmp_path / "ds")
    empties = [i for i in range(10) if json.loads((tmp_path / f"ds/samples/{i:06d}/params.json").read_text())
               .get("empty")]
    assert empties == [1, 7, 9] and ds.indices(empty=True) == empties
    assert ds.indices() == [0, 2, 3, 4, 5, 6, 8]  # training and evaluation see parts only
    assert ds.indices("test", empty=None) == [0, 1] and ds.indices("test") == [0]
    with pytest.raises(SimError, match=r"empty rate must be in \[0, 1\]"):
        sd.DatasetSpec(empty_rate=1.5)


def test_render_cli_takes_an_empty_rate(tmp_path, capsys) -> None:
    from station.cli import main

    out = tmp_path / "x"
    assert main(["render", "--out", str(out), "--count", "1", "--empty-rate", "2"]) == 2
    assert "empty rate must be in [0, 1]" in capsys.readouterr().err and not out.exists()
