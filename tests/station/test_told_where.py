"""``station eval``'s "told where to look" rows: per type, what the localised oracle separates and what the model
caught of it; parts without a mask are left out, no threshold leaves ``caught`` NaN, the plot is written."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import torch

from station.told_where import COLUMNS, plot, told_where
from tests.model.test_localised_oracle import blob_mask
from tests.model.test_variation import H, W, fitted, parts


def test_rows_per_type_count_only_masked_defects_and_say_what_the_model_caught(tmp_path: Path) -> None:
    vm = fitted()
    x = torch.cat([parts(100, 21), parts(8, 22, defect=True), parts(8, 23)])
    labels = np.r_[np.zeros(100), np.ones(16)].astype(int)
    masks = torch.cat([torch.zeros(100, H, W, dtype=torch.bool), blob_mask(16)])
    known = np.ones(116, bool)
    known[-1] = False  # an imported defect without a mask: not judged by the oracle
    types = [""] * 100 + ["dent"] * 8 + ["scratch"] * 8
    scores = np.r_[np.zeros(100), np.ones(4), np.zeros(12)]  # the model caught half of the dents, no scratch
    rows, per_part = told_where(vm, x, labels, masks, known, types, scores, threshold=0.5)
    assert [r["type"] for r in rows] == ["all", "dent", "scratch"] and list(rows[0]) == COLUMNS
    assert [r["defects"] for r in rows] == [15, 8, 7]
    dent, scratch = rows[1], rows[2]
    assert dent["separable"] == 1.0 and dent["caught"] == 0.5 and dent["caught_of_separable"] == 0.5
    assert dent["image_auroc_separable"] == 0.75  # 4 of the 8 separable dents above all 100 good parts, 4 tied
    assert scratch["separable"] <= 2 / 7 and scratch["caught"] == 0.0  # unchanged parts: at most chance
    assert per_part[:100] == [None] * 100 and per_part[-1] is None  # good parts, and the defect without a mask
    assert per_part[100:108] == [True] * 8 and sum(per_part[108:115]) == round(scratch["separable"] * 7)
    unthresholded, _ = told_where(vm, x, labels, masks, known, types, scores, threshold=None)
    assert math.isnan(unthresholded[0]["caught"]) and unthresholded[0]["separable"] == rows[0]["separable"]
    assert told_where(vm, x[:100], labels[:100], masks[:100], known[:100], types[:100], scores[:100], 0.5) == (
        [], [None] * 100)
    assert (tmp_path / plot(tmp_path, rows)).stat().st_size > 1000
