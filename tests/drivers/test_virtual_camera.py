"""The virtual camera over a small dataset written through ``sim.dataset`` (the format's own writer)."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest

from drivers.camera import Camera, CameraConfig
from drivers.errors import CameraConfigError, CameraError, CameraTimeout
from drivers.virtual_camera import VirtualCamera, VirtualCameraConfig
from sim.dataset import DatasetSpec, Sample, init_dataset, split_of, write_sample

W, H = 32, 24


def make_dataset(root: Path, n: int = 12, defective: tuple[int, ...] = (0, 1, 3)) -> Path:
    init_dataset(root, DatasetSpec(width=W, height=H), n)
    for i in range(n):
        mask = np.zeros((H, W), bool)
        if i in defective:
            mask[4:8, 4:8] = True
        raw = np.full((H, W), i, np.uint8)  # the sample's index in every pixel: tells which part a frame shows
        label = int(mask.any())
        s = Sample(i, raw, {"index": i, "split": split_of(i), "label": label,
                            "defect": {"type": "dent"} if label else None}, label, split_of(i),
                   defect_mask=mask, object_mask=np.ones((H, W), bool))
        write_sample(root, s)
    return root


def cam(root: Path, **kw: object) -> VirtualCamera:
    sim_kw = {k: kw.pop(k) for k in ("defect_rate", "split", "seed", "cache_mb", "empty_rate") if k in kw}
    cfg = CameraConfig(**{"trigger": "free_run", "frame_rate_hz": 500.0, **kw})  # type: ignore[arg-type]
    return VirtualCamera(cfg, VirtualCameraConfig(str(root), **sim_kw))  # type: ignore[arg-type]


def test_frames_carry_matching_ground_truth(tmp_path: Path) -> None:
    root = make_dataset(tmp_path / "ds")
    c = cam(root, defect_rate=0.5)
    assert isinstance(c, Camera)
    with c:
        c.start()
        frames = [c.grab() for _ in range(200)]
    labels = np.array([f.ground_truth.label for f in frames])
    assert 0.38 < labels.mean() < 0.62  # defect_rate 0.5
    for f in frames:
        gt = f.ground_truth
        assert f.raw.shape == (H, W) and f.bit_depth == 8 and f.pixel_format == "Mono8"
        assert int(f.raw[0, 0]) == gt.sample_index  # the frame shows the sample its truth describes
        assert gt.label == int(gt.defect_mask.any()) and gt.label == (gt.sample_index in (0, 1, 3))
        assert not f.raw.flags.writeable
    assert [f.frame_id for f in frames] == list(range(1, 201))
    assert len({f.ground_truth.sample_index for f in frames}) == 12  # random order over every part
    assert c.statistics().completed == 200


def test_free_run_keeps_the_frame_rate(tmp_path: Path) -> None:
    with cam(make_dataset(tmp_path / "ds"), frame_rate_hz=100.0) as c:
        c.start()
        c.grab()
        t = time.perf_counter()
        for _ in range(20):
            c.grab()
        rate = 20 / (time.perf_counter() - t)
    assert 80 < rate < 110


def test_software_trigger_one_frame_per_trigger(tmp_path: Path) -> None:
    with cam(make_dataset(tmp_path / "ds"), trigger="software") as c:
        c.start()
        with pytest.raises(CameraTimeout, match="no trigger within 50 ms"):
            c.grab(timeout_ms=50)
        c.trigger()
        c.trigger()
        assert c.grab().frame_id == 1 and c.grab().frame_id == 2
        with pytest.raises(CameraTimeout):
            c.grab(timeout_ms=20)
        assert c.statistics().timeouts == 2


def test_config_errors(tmp_path: Path) -> None:
    root = make_dataset(tmp_path / "ds", defective=())
    with pytest.raises(CameraConfigError, match="has no sample with a defect"):
        cam(root, defect_rate=0.2).open()
    with cam(root, defect_rate=0.0) as c:  # good parts only is fine
        c.start()
        assert c.grab().ground_truth.label == 0
    with pytest.raises(CameraConfigError, match=r"region 64x48 but .* holds 32x24"):
        cam(root, defect_rate=0.0, width=64, height=48).open()
    with pytest.raises(CameraConfigError, match="hardware lines"):
        cam(root, trigger="line0").open()
    with pytest.raises(CameraError, match="grab before start"):
        cam(root, defect_rate=0.0).grab()
    from sim.errors import SimError

    with pytest.raises(SimError, match=r"manifest\.json is missing"):
        cam(tmp_path / "nothing").open()
