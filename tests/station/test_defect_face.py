"""Detection by face: the defects on each face of the part, all types and each, caught and ranked."""

from __future__ import annotations

import math

from sim.defects import defect_face
from station.defect_face import by_face

TOP, FRONT = {"type": "dent", "normal": [0, 0, 1]}, {"type": "dent", "normal": [0, -1, 0]}


def test_each_face_says_how_many_of_its_defects_are_caught() -> None:
    records = [None, None, None, TOP, TOP, {"type": "scratch", "normal": [0, 0, 1]}, FRONT, FRONT, {"type": "dent"}]
    labels = [0, 0, 0, 1, 1, 1, 1, 1, 1]
    types = ["", "", "", "dent", "dent", "scratch", "dent", "dent", "dent"]
    scores = [0.1, 0.2, 0.3, 0.9, 0.8, 0.25, 0.05, 0.02, 0.99]
    faces = [defect_face(r) for r in records]
    rows = by_face(faces, labels, scores, 0.5, types)
    assert [(r["face"], r["type"], r["defects"]) for r in rows] == [
        ("top", "all", 3), ("top", "dent", 2), ("top", "scratch", 1), ("front", "all", 2), ("front", "dent", 2)]
    caught = {(r["face"], r["type"]): r["caught"] for r in rows}
    assert caught == {("top", "all"): 2 / 3, ("top", "dent"): 1.0, ("top", "scratch"): 0.0, ("front", "all"): 0.0,
                      ("front", "dent"): 0.0}
    auc = {(r["face"], r["type"]): r["image_auroc"] for r in rows}
    assert auc[("top", "dent")] == 1.0 and auc[("front", "dent")] == 0.0
    assert abs(auc[("top", "scratch")] - 2 / 3) < 1e-12  # 0.25 against good parts at 0.1, 0.2 and 0.3
    # the defect without a face (no normal) is in no row; none at all: no rows; no threshold: caught unknown
    assert by_face([None, defect_face({"type": "dent"})], [0, 1], [0.1, 0.9], 0.5, ["", "dent"]) == []
    assert math.isnan(by_face(faces, labels, scores, None, types)[0]["caught"])
