"""Frame, CameraConfig and frame-id unwrapping: the parts every camera shares."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from drivers.camera import CameraConfig, FrameIdTracker, backoff_delays_s, sensor_region
from drivers.errors import CameraConfigError
from drivers.frame import Frame


def test_frame_checks_and_properties() -> None:
    f = Frame(np.zeros((4, 6), np.uint16), "Mono12p", 12, 1, 0, 0)
    assert (f.height, f.width, f.full_scale) == (4, 6, 4095)
    with pytest.raises(ValueError, match="frame 7: bit depth 12 does not fit uint8"):
        Frame(np.zeros((4, 6), np.uint8), "Mono8", 12, 7, 0, 0)
    with pytest.raises(ValueError, match="2-D"):
        Frame(np.zeros((4, 6, 3), np.uint8), "Mono8", 8, 7, 0, 0)


def test_config_rejects_odd_region_and_unknown_trigger() -> None:
    with pytest.raises(CameraConfigError, match="width = 5"):
        CameraConfig(width=5)
    with pytest.raises(CameraConfigError, match="'hardware'"):
        CameraConfig(trigger="hardware")


def test_frame_id_wraps_from_65535_to_1() -> None:
    t = FrameIdTracker()
    got = [t.update(i) for i in (65533, 65534, 65535, 1, 2)]
    assert [u for u, _ in got] == [1, 2, 3, 4, 5] and all(lost == 0 for _, lost in got)


def test_frame_id_gaps_count_lost_frames_across_the_wrap() -> None:
    t = FrameIdTracker()
    t.update(65534)
    assert t.update(2) == (4, 2)  # 65535 and 1 lost
    t.restart()
    assert t.update(100) == (5, 0)  # after a restart: no gap counted, still monotonic


def test_frame_id_0_is_unknown_and_moves_nothing() -> None:
    """Aravis gives id 0 to a buffer whose leader was lost. Taken as the first id, it made the camera's real ids (the
    fake camera's ran from 65402) look 133 frames behind it: every frame was late, none delivered, and a grab timed
    out (the packet-loss case failed about 1 run in 20)."""
    t = FrameIdTracker()
    assert t.update(0) == (0, 0)  # not counted, not delivered (0 is never a new id)
    assert [t.update(i) for i in (65402, 65403, 65405)] == [(1, 0), (2, 0), (4, 1)]
    assert t.update(0) == (4, 0) and t.update(65406) == (5, 0)


def test_reordered_frame_ids_are_late_frames_not_a_wrap() -> None:
    """Packet loss with resends completes frames out of order: an id just behind the last one is a late frame that
    was counted lost when its gap was seen (it was taken as a 16-bit wrap: 65534 lost frames each time)."""
    t = FrameIdTracker()
    t.update(100)
    assert t.update(102) == (3, 1)  # 101 missing so far
    assert t.update(101) == (2, -1)  # 101 arrived late: no longer lost
    assert t.update(101) == (2, 0)  # the same id again: nothing to count
    assert t.update(103) == (4, 0)
    t2 = FrameIdTracker()  # across the wrap too
    t2.update(65535)
    assert t2.update(2) == (3, 1)
    assert t2.update(1) == (2, -1)
    lost = 0
    t3 = FrameIdTracker()  # a lossy stream: the net count never exceeds the ids skipped
    for i in [1, 3, 2, 5, 4, 7, 6, 6, 9, 8, 10]:
        lost += t3.update(i)[1]
    assert lost == 0


def test_a_region_beyond_the_sensor_is_refused_naming_the_keys() -> None:
    assert sensor_region(CameraConfig(width=320, height=240, offset_x=2), 640, 480) == (2, 0, 320, 240)
    assert sensor_region(CameraConfig(offset_x=40), 640, 480) == (40, 0, 600, 480)
    with pytest.raises(CameraConfigError, match="offset_x \\+ width = 0 \\+ 4000"):
        sensor_region(CameraConfig(width=4000, height=4000), 640, 480)
    with pytest.raises(CameraConfigError, match="offset_y"):
        sensor_region(CameraConfig(offset_y=480), 640, 480)


def test_extended_ids_do_not_wrap() -> None:
    t = FrameIdTracker()
    t.update(70000)
    assert t.update(70003) == (4, 2)


def test_backoff_doubles_and_caps() -> None:
    assert list(backoff_delays_s(0.5, 3.0, 5)) == [0.5, 1.0, 2.0, 3.0, 3.0]


def test_drivers_import_without_torch() -> None:
    code = ("import sys; import drivers.camera, drivers.pixel_formats, drivers.frame, drivers.line_io, "
            "drivers.plc_sim, drivers.aravis_camera, drivers.virtual_camera, drivers.gv_server; "
            "assert 'torch' not in sys.modules, 'torch imported'")
    subprocess.run([sys.executable, "-c", code], check=True)
