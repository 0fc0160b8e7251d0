"""Images of rejected parts: one file per reject, never shared by two rows, and retention deletes only its own."""

from __future__ import annotations

import os
import time

import numpy as np

from station.inspection_log import InspectionLog, InspectionRecord
from station.reject_store import RejectStore


def test_two_rejects_with_the_same_part_and_frame_ids_keep_two_images(tmp_path):
    """A restarted station (part and frame ids start over) rejecting part 7 on frame 7 again the same day overwrote
    the first image: its row showed the other part, and retention of the older row then deleted the image the kept
    row pointed to."""
    store, log = RejectStore(tmp_path / "rejects", reserve_bytes=0), InspectionLog(tmp_path / "log.sqlite")
    now = time.time()
    first = store.save("7", 7, np.full((4, 4), 11, np.uint8), None)
    log.append(InspectionRecord("reject", now - 20 * 3600, part_id="7", camera_frame_id=7, image_path=first))
    second = store.save("7", 7, np.full((4, 4), 99, np.uint8), None)
    log.append(InspectionRecord("reject", now, part_id="7", camera_frame_id=7, image_path=second))
    assert first != second and int(np.load(first)["raw"][0, 0]) == 11
    store.delete(log.apply_retention(1.0, now_unix_s=now + 5 * 3600))
    assert [os.path.exists(r["image_path"]) for r in log.rows()] == [True]
    assert store.save("lot 4/17", 3, np.zeros((2, 2), np.uint8), None) != store.save(
        "lot_4_17", 3, np.zeros((2, 2), np.uint8), None)


def test_retention_deletes_nothing_outside_the_image_folder(tmp_path):
    victim = tmp_path / "important.txt"
    victim.write_text("x")
    elsewhere = tmp_path / "other" / "a.npz"
    elsewhere.parent.mkdir()
    elsewhere.write_bytes(b"x")
    store = RejectStore(tmp_path / "rejects", reserve_bytes=0)
    own = store.save("P1", 1, np.zeros((2, 2), np.uint8), None)
    assert store.delete([str(victim), str(elsewhere), str(tmp_path / "rejects" / ".." / "important.txt"), own]) == 1
    assert victim.exists() and elsewhere.exists() and not os.path.exists(own)
