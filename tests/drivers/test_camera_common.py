"""Frame, CameraConfig and frame-id unwrapping: the parts every camera shares."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from drivers.camera import CameraConfig, FrameIdTracker, backoff_delays_s
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
