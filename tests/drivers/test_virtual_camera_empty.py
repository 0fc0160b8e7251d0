"""The virtual camera's empty views: drawn at ``empty_rate``, ground truth ``present`` False, and a clear error
naming the set when it has none."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from test_virtual_camera import H, W, cam, make_dataset  # same folder (pytest puts it on sys.path)

from drivers.errors import CameraConfigError
from sim.dataset import DatasetSpec, Sample, init_dataset, is_empty, split_of, write_sample


def make_dataset_with_empties(root: Path, n: int = 20, seed: int = 3) -> Path:
    """Samples showing their index in every pixel; the empty ones (``sim.dataset.is_empty`` at rate 0.5) are
    marked as ``station render --empty-rate`` marks them; odd parts are defective."""
    init_dataset(root, DatasetSpec(seed=seed, width=W, height=H, empty_rate=0.5), n)
    for i in range(n):
        empty = is_empty(seed, i, 0.5)
        mask = np.zeros((H, W), bool)
        if i % 2 and not empty:
            mask[4:8, 4:8] = True
        label = int(mask.any())
        params = {"index": i, "split": split_of(i), "label": label, "defect": {"type": "dent"} if label else None,
                  **({"empty": True} if empty else {})}
        write_sample(root, Sample(i, np.full((H, W), i, np.uint8), params, label, split_of(i), defect_mask=mask,
                                  object_mask=np.zeros((H, W), bool) if empty else np.ones((H, W), bool)))
    return root


def test_empty_views_come_at_their_rate_with_their_truth(tmp_path: Path) -> None:
    root = make_dataset_with_empties(tmp_path / "ds")
    empties = {i for i in range(20) if is_empty(3, i, 0.5)}
    with cam(root, defect_rate=0.5, empty_rate=0.3) as c:
        c.start()
        frames = [c.grab() for _ in range(300)]
    absent = np.array([not f.ground_truth.present for f in frames])
    assert 0.22 < absent.mean() < 0.38
    for f in frames:
        gt = f.ground_truth
        assert int(f.raw[0, 0]) == gt.sample_index and gt.present == (gt.sample_index not in empties)
        assert gt.label == 0 or gt.present
    parts = [f.ground_truth.label for f in frames if f.ground_truth.present]
    assert 0.38 < np.mean(parts) < 0.62  # defect_rate counts among the parts shown


def test_no_empty_views_by_default_and_an_error_when_the_set_has_none(tmp_path: Path) -> None:
    with cam(make_dataset_with_empties(tmp_path / "e"), defect_rate=0.5) as c:
        c.start()
        assert all(c.grab().ground_truth.present for _ in range(50))
    plain = make_dataset(tmp_path / "plain")
    with pytest.raises(CameraConfigError, match=r"empty_rate 0.2 but .*plain \(split 'test'\) has no empty sample"):
        cam(plain, empty_rate=0.2, split="test").open()
    with pytest.raises(CameraConfigError, match=r"empty_rate = 1.5: must be in \[0, 1\]"):
        cam(plain, empty_rate=1.5)
