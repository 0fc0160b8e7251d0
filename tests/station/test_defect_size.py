"""Detection by defect size (``station.defect_size``, ``sim.defects.defect_size``): the physical size per type,
and thirds of each type's defects by it, with what was caught."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sim.defects import apparent_size, defect_size
from station.defect_size import detection_by_size


def test_each_type_has_the_size_that_governs_it() -> None:
    name, slope = defect_size({"type": "dent", "radius_mm": 2.0, "depth_mm": 0.2})
    assert name == "slope_deg" and slope == pytest.approx(math.degrees(math.atan(math.pi / 2 * 0.1)))
    assert defect_size({"type": "scratch", "length_mm": 10.0, "width_mm": 0.5}) == ("area_mm2", 5.0)
    assert defect_size({"type": "stain", "radius_mm": 1.5}) == ("radius_mm", 1.5)
    assert defect_size({"type": "chip", "size_mm": 0.7}) == ("size_mm", 0.7)
    assert defect_size({"type": "missing_stud", "radius_mm": 2.4}) is None  # all alike
    # the kinds nobody trained on: a blister's steepest tilt as a dent's, a particle's radius
    name, slope = defect_size({"type": "blister", "radius_mm": 2.0, "height_mm": 0.2})
    assert name == "slope_deg" and slope == pytest.approx(math.degrees(math.atan(math.pi / 2 * 0.1)))
    assert defect_size({"type": "debris", "radius_mm": 0.3, "grey": 0.5}) == ("radius_mm", 0.3)
    assert defect_size(None) is None and defect_size({"type": "dent", "radius_mm": 2.0}) is None
    assert apparent_size({"type": "missing_stud", "visible_px": 1600}) == ("visible_px", 1600.0)  # every type
    assert apparent_size({"type": "dent"}) is None and apparent_size(None) is None


def test_thirds_by_size_say_which_defects_are_caught() -> None:
    """Six dents, the three steepest scored above the threshold: the upper thirds are caught, the lowest is not."""
    labels = [0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1]
    slopes = [None] * 4 + [("slope_deg", v) for v in (5.0, 1.0, 9.0, 2.0, 7.0, 3.0)] + [None]
    scores = [0.1, 0.2, 0.3, 0.4, 0.6, 0.05, 0.9, 0.15, 0.8, 0.5, 0.7]
    types = [""] * 4 + ["dent"] * 6 + ["missing_stud"]
    rows = detection_by_size(labels, scores, 0.45, slopes, types)
    assert [(r["range"], r["defects"], r["caught"]) for r in rows] == [("1-2", 2, 0.0), ("3-5", 2, 1.0),
                                                                        ("7-9", 2, 1.0)]
    assert all(r["type"] == "dent" and r["size"] == "slope_deg" for r in rows)
    assert rows[0]["image_auroc"] == pytest.approx(0.125) and rows[2]["image_auroc"] == 1.0
    assert math.isnan(detection_by_size(labels, scores, None, slopes, types)[0]["caught"])
    assert detection_by_size(labels, scores, 0.45, [None] * 11, types) == []
    big = [None] * 4 + [("visible_px", v) for v in (1840.0, 12.0, 2720.0, 950.0, 99.5, 1000.0)] + [None]
    assert [r["range"] for r in detection_by_size(labels, scores, 0.45, big, types)] == ["12-99.5", "950-1000",
                                                                                         "1840-2720"]
    assert np.isnan(detection_by_size([1, 1], [0.5, 0.6], 0.4, [("size_mm", 1.0), ("size_mm", 2.0)],
                                      ["chip", "chip"])[0]["image_auroc"])  # no good parts
