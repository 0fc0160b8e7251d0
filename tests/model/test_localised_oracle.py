"""The localised oracle: told where a defect is, it separates a change the features show from good parts, never one
they do not show, nor a mask off the judged part."""

from __future__ import annotations

import numpy as np
import pytest
import torch

from model.draem.localised_oracle import localised_oracle, statistics
from tests.model.test_variation import H, W, fitted, parts


def blob_mask(n: int, dy: float = 0.0, dx: float = -8.0) -> torch.Tensor:
    """(n, H, W) bool: where ``parts(defect=True)`` puts its dent-like change (centre offset (dy, dx), 3 px)."""
    y, x = np.mgrid[0:H, 0:W]
    m = (y - H / 2 - dy) ** 2 + (x - W / 2 - dx) ** 2 <= 9
    return torch.from_numpy(np.repeat(m[None], n, 0))


def test_statistics_are_the_mean_chi_square_and_the_chi_square_of_the_mean() -> None:
    z = np.zeros((1, 2, 4), np.float32)
    z[0, 0] = [2.0, -2.0, 5.0, 0.0]  # the mask holds pixels 0 and 1; pixel 2 is outside it
    z[0, 1] = [1.0, 1.0, 0.0, 7.0]  # pixel 3 is in the mask but not judged
    judged = np.array([[1, 1, 1, 0]], np.float32)
    masks = np.array([[1, 1, 0, 1], [0, 0, 0, 1]], np.float32)
    s = statistics(z, judged, masks)
    assert s[0, 0, 0] == pytest.approx(5.0)  # ((4 + 1) + (4 + 1)) / 2
    assert s[0, 0, 1] == pytest.approx(1.0)  # channel means 0 and 1
    assert s[0, 1].tolist() == [0.0, 0.0]  # no judged pixel under the second mask


def test_the_oracle_separates_a_change_the_features_show_and_not_one_they_do_not() -> None:
    vm = fitted()
    good, shown, unseen = parts(100, 11), parts(12, 12, defect=True), parts(12, 13)
    x = torch.cat([good, shown, unseen])
    labels = np.r_[np.zeros(100), np.ones(24)].astype(int)
    masks = torch.cat([torch.zeros(100, H, W, dtype=torch.bool), blob_mask(24)])
    res = localised_oracle(vm, x, labels, masks)
    assert res.defect.shape == res.limit.shape == (24, 2)
    assert np.isfinite(res.defect).all() and np.isfinite(res.limit).all()
    assert res.separable[:12].all()  # the dent-like change: every one, told where
    assert res.separable[12:].sum() <= 2  # good parts labelled defective: about 2 % by chance, by either statistic
    # a mask on the belt, off the judged part, separates nothing
    off = localised_oracle(vm, x, labels, torch.cat([masks[:100], blob_mask(24, dy=-H / 2 + 2, dx=-W / 2 + 3)]))
    assert not off.separable.any()


def test_a_set_without_good_or_defective_parts_is_refused() -> None:
    vm = fitted()
    x = parts(4, 3)
    with pytest.raises(ValueError, match="good and defective"):
        localised_oracle(vm, x, np.zeros(4, int), blob_mask(4))
    with pytest.raises(ValueError, match="false_reject"):
        localised_oracle(vm, x, np.array([0, 0, 1, 1]), blob_mask(4), false_reject=1.0)
