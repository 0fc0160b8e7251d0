"""Two cameras as one: a part's two frames kept together, a virtual second camera showing the first's part, and every
fault of the second camera raised with its name (the station then rejects the part)."""

from __future__ import annotations

import json
import time
from pathlib import Path

import numpy as np
import pytest

from drivers.camera import Camera, CameraBase, CameraConfig
from drivers.camera_pair import CameraPair
from drivers.errors import CameraConfigError, CameraLost, CameraTimeout
from drivers.frame import Frame
from drivers.virtual_camera import VirtualCamera, VirtualCameraConfig
from sim.dataset import DatasetSpec, Sample, init_dataset, split_of, write_sample

W, H = 32, 24


def make_set(root: Path, offset: int, defective: tuple[int, ...] = (0, 1, 3), n: int = 12) -> Path:
    """``n`` samples whose every pixel is ``offset`` + the sample's index (which camera, which part)."""
    init_dataset(root, DatasetSpec(width=W, height=H), n)
    for i in range(n):
        mask = np.zeros((H, W), bool)
        if i in defective:
            mask[4:8, 4:8] = True
        label = int(mask.any())
        defect = {"type": "dent", "centre_m": [0.001 * i, 0.0, 0.0], "visible_px": 16 + offset} if label else None
        write_sample(root, Sample(i, np.full((H, W), offset + i, np.uint8),
                                  {"index": i, "split": split_of(i), "label": label, "defect": defect}, label,
                                  split_of(i),
                                  defect_mask=mask, object_mask=np.ones((H, W), bool)))
    return root


def virtual_pair(tmp_path: Path, twin_defective: tuple[int, ...] = (0, 1, 3)) -> CameraPair:
    cfg = CameraConfig(trigger="software", frame_rate_hz=1000.0)
    first = VirtualCamera(cfg, VirtualCameraConfig(str(make_set(tmp_path / "line", 0)), defect_rate=0.5, seed=3))
    second = VirtualCamera(cfg, VirtualCameraConfig(str(make_set(tmp_path / "side", 100, twin_defective))),
                           leader=first)
    return CameraPair(first, second, max_skew_ms=100.0)


def test_the_second_camera_shows_the_first_cameras_part(tmp_path: Path) -> None:
    pair = virtual_pair(tmp_path)
    assert isinstance(pair, Camera)
    with pair:
        pair.start()
        frames = []
        for _ in range(60):
            pair.trigger()
            frames.append(pair.grab())
    shown = [int(f.raw[0, 0]) for f in frames]
    assert len(set(shown)) > 6  # parts in random order ...
    for f in frames:  # ... each seen by both cameras
        assert f.companion is not None and int(f.companion.raw[0, 0]) == int(f.raw[0, 0]) + 100
        assert f.companion.ground_truth.label == f.ground_truth.label
        assert f.companion.companion is None
    assert pair.statistics().completed == 60 and pair.second_statistics().completed == 60


def test_a_twin_set_of_other_parts_is_refused(tmp_path: Path) -> None:
    pair = virtual_pair(tmp_path, twin_defective=(0, 1, 4))
    with pytest.raises(CameraConfigError, match=r"sample [34] of .*side .* is not the part sample [34] of .*line"):
        pair.open()


def test_a_defect_one_camera_does_not_see_is_still_the_same_part(tmp_path: Path) -> None:
    """Twin sets' labels say what each camera sees: a front-face dent is label 0 for the line camera, 1 for the side
    camera. The part is the same (the drawn defect), and the pair is accepted."""
    pair = virtual_pair(tmp_path)
    root = tmp_path / "line" / "samples" / "000003"
    params = json.loads((root / "params.json").read_text())
    unseen = {**params, "label": 0, "defect": {**params["defect"], "visible_px": 0}}
    (root / "params.json").write_text(json.dumps(unseen))
    with pair:
        pair.start()
        for _ in range(40):
            pair.trigger()
            f = pair.grab()
            if int(f.raw[0, 0]) == 3:
                assert (f.ground_truth.label, f.companion.ground_truth.label) == (0, 1)
                break
        else:
            pytest.fail("sample 3 never drawn")


class Scripted(CameraBase):
    """Frames at given host times (ms from ``t0``); an exception entry is raised."""

    def __init__(self, times_ms: list[float | Exception], t0_ns: int) -> None:
        super().__init__(CameraConfig(trigger="software"))
        self.script, self.t0_ns, self.n = list(times_ms), t0_ns, 0

    def open(self) -> None: ...
    def close(self) -> None: ...
    def start(self) -> None: ...
    def stop(self) -> None: ...
    def configure(self, config: CameraConfig) -> None: ...
    def trigger(self) -> None: ...

    def grab(self, timeout_ms: int | None = None) -> Frame:
        if not self.script:
            raise CameraTimeout("no frame within 5 ms")
        item = self.script.pop(0)
        if isinstance(item, Exception):
            raise item
        self.n += 1
        return Frame(np.zeros((4, 4), np.uint8), "Mono8", 8, self.n, 0, self.t0_ns + int(item * 1e6))


def scripted_pair(first: list[float | Exception], second: list[float | Exception]) -> CameraPair:
    t0 = time.time_ns()
    return CameraPair(Scripted(first, t0), Scripted(second, t0), max_skew_ms=20.0)


def test_an_earlier_parts_second_frame_is_skipped() -> None:
    pair = scripted_pair([100.0, 200.0], [5.0, 101.0, 203.0])  # frame 1 of the second camera came after its part
    a, b = pair.grab(), pair.grab()
    assert (a.frame_id, a.companion.frame_id) == (1, 2) and (b.frame_id, b.companion.frame_id) == (2, 3)
    assert pair.unpaired == 1


def test_a_missed_pulse_rejects_the_part_and_keeps_the_frame_for_the_next() -> None:
    pair = scripted_pair([100.0, 200.0], [199.0])  # the second camera missed part 1's pulse
    with pytest.raises(CameraTimeout, match=r"second camera: .* came 99 ms after .* it missed this part"):
        pair.grab()
    b = pair.grab()
    assert (b.frame_id, b.companion.frame_id) == (2, 1)


def test_second_camera_faults_name_it() -> None:
    with pytest.raises(CameraTimeout, match=r"^second camera: no frame within"):
        scripted_pair([100.0], []).grab()
    with pytest.raises(CameraLost, match=r"^second camera: unplugged"):
        scripted_pair([100.0], [CameraLost("unplugged")]).grab()
    with pytest.raises(CameraTimeout, match=r"^no frame within"):  # the first camera's own: as without a pair
        scripted_pair([], [100.0]).grab()
