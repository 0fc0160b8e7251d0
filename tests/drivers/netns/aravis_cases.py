"""Aravis driver cases over real GigE Vision (arv-fake-gv-camera-0.8 on loopback).

Not collected by the default run: ``tests/drivers/test_aravis.py`` runs this file with pytest inside a private
network namespace (loopback only), as the network rule requires. Run it alone the same way:
    unshare -n sh -c 'ip link set lo up && exec .venv/bin/python -m pytest tests/drivers/netns/aravis_cases.py'
"""

from __future__ import annotations

import contextlib
import itertools
import subprocess
import threading
import time
from collections.abc import Iterator

import numpy as np
import pytest

from drivers.aravis_camera import AravisCamera, list_cameras
from drivers.camera import CameraConfig
from drivers.errors import CameraConfigError, CameraError, CameraLost, CameraNotFound, CameraTimeout
from drivers.netns import in_private_netns

pytestmark = pytest.mark.skipif(not in_private_netns(), reason="GigE Vision only inside a private network namespace")

SERIAL = "PA0001"


class FakeGv:
    """arv-fake-gv-camera-0.8 serving on 127.0.0.1."""

    def __init__(self, lost_per_mille: int = 0) -> None:
        self.lost_per_mille = lost_per_mille
        self.proc: subprocess.Popen[bytes] | None = None

    def start(self) -> FakeGv:
        argv = ["arv-fake-gv-camera-0.8", "-i", "127.0.0.1", "-s", SERIAL]
        if self.lost_per_mille:
            argv += ["-r", str(self.lost_per_mille)]
        self.proc = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(0.3)  # it binds its GVCP socket at once; give the process time to start
        return self

    def kill(self) -> None:
        if self.proc and self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


@pytest.fixture
def fake() -> Iterator[FakeGv]:
    f = FakeGv().start()
    yield f
    f.kill()


def cfg(**kw: object) -> CameraConfig:
    base = dict(device="127.0.0.1", width=64, height=48, frame_rate_hz=200.0, trigger="free_run", timeout_ms=1000,
                reconnect=False, packet_size=1400)
    base.update(kw)
    return CameraConfig(**base)  # type: ignore[arg-type]


def ramp(frame_device_id: int, h: int, w: int) -> np.ndarray:
    """The fake camera's Mono8 test image at exposure 10 ms, gain 0: (x + y + frame id) % 255."""
    y, x = np.mgrid[:h, :w]
    return ((x + y + frame_device_id) % 255).astype(np.uint8)


def test_grab_frames_with_content_and_metadata(fake: FakeGv) -> None:
    with AravisCamera(cfg(width=640, height=480, frame_rate_hz=100.0)) as cam:
        cam.start()
        frames = [cam.grab() for _ in range(10)]
        cam.stop()
        stats = cam.statistics()
    assert all(f.raw.shape == (480, 640) and f.raw.dtype == np.uint8 and f.bit_depth == 8 for f in frames)
    assert [f.frame_id for f in frames] == list(range(frames[0].frame_id, frames[0].frame_id + 10))
    for f in frames:
        np.testing.assert_array_equal(f.raw, ramp(f.device_frame_id, 480, 640))
    assert all(b.timestamp_ns > a.timestamp_ns for a, b in itertools.pairwise(frames))
    assert abs(frames[-1].host_timestamp_ns - time.time_ns()) < 5e9
    assert (stats.completed, stats.failed, stats.dropped) == (10, 0, 0)


def test_mono16(fake: FakeGv) -> None:
    with AravisCamera(cfg(pixel_format="Mono16")) as cam:
        cam.start()
        f = cam.grab()
    assert f.raw.dtype == np.uint16 and f.bit_depth == 16 and f.pixel_format == "Mono16" and f.raw.max() > 255


def test_frame_ids_increase_across_the_16bit_wrap(fake: FakeGv) -> None:
    with AravisCamera(cfg(frame_rate_hz=400.0)) as cam:
        cam.start()
        first = cam.grab()
        frames = [first]
        while frames[-1].device_frame_id >= first.device_frame_id and len(frames) < 400:
            frames.append(cam.grab())
        frames += [cam.grab() for _ in range(3)]
        stats = cam.statistics()
    ids = [f.device_frame_id for f in frames]
    assert ids[-4] < ids[0], f"no wrap seen: {ids[0]}..{ids[-1]}"
    unwrapped = [f.frame_id for f in frames]
    assert all(b - a == 1 for a, b in itertools.pairwise(unwrapped)), "gap or repeat across the wrap"
    assert stats.dropped == 0


def test_software_trigger(fake: FakeGv) -> None:
    with AravisCamera(cfg(trigger="software")) as cam:
        cam.start()
        with pytest.raises(CameraTimeout, match="no complete frame within 300 ms"):
            cam.grab(timeout_ms=300)
        got = []
        for _ in range(4):
            cam.trigger()
            got.append(cam.grab())
        with pytest.raises(CameraTimeout):
            cam.grab(timeout_ms=200)  # one frame per trigger, none in free run
        stats = cam.statistics()
    assert [f.frame_id - got[0].frame_id for f in got] == [0, 1, 2, 3]
    assert stats.timeouts == 2 and stats.completed == 4


def test_binning_another_tool_left_is_undone(fake: FakeGv) -> None:
    """A vendor viewer or a saved user set left the camera binned 2x2: the driver streamed a mosaic whose
    polarizer angles were mixed, as if it were raw."""
    with AravisCamera(cfg(trigger="software")) as other:
        other._camera.set_integer("BinningHorizontal", 2)
        other._camera.set_integer("BinningVertical", 2)
    with AravisCamera(cfg(trigger="software")) as cam:
        assert (cam._camera.get_integer("BinningHorizontal"), cam._camera.get_integer("BinningVertical")) == (1, 1)
        cam.start()
        cam.trigger()
        assert cam.grab(2000).raw.shape == (48, 64)
        cam.stop()


def test_trigger_in_free_run_is_an_error(fake: FakeGv) -> None:
    with AravisCamera(cfg()) as cam:
        cam.start()
        with pytest.raises(CameraError, match="trigger = 'software'"):
            cam.trigger()


def test_packet_loss_is_counted_and_no_corrupt_frame_is_delivered() -> None:
    f = FakeGv(lost_per_mille=60).start()
    try:
        with AravisCamera(cfg(width=128, height=96)) as cam:  # 12 KiB: ~9 data packets per frame
            cam.start()
            frames = [cam.grab() for _ in range(25)]
            cam.stop()
            stats = cam.statistics()
    finally:
        f.kill()
    for fr in frames:
        np.testing.assert_array_equal(fr.raw, ramp(fr.device_frame_id, 96, 128))
    assert stats.failed > 0 and stats.missing_packets > 0, stats
    assert stats.failed_by_status.get("missing-packets", 0) > 0
    # every frame id up to the last delivered one is accounted for: delivered, incomplete or lost on the way
    assert frames[-1].frame_id == stats.completed + stats.failed + stats.dropped


def test_frames_completed_out_of_order_under_loss_are_never_a_wrap() -> None:
    """2 % loss at 256 x 256: resends complete frames out of order; ids behind the newest were taken for a 16-bit
    wrap (65534 lost frames each, 'dropped 655350')."""
    f = FakeGv(lost_per_mille=20).start()
    try:
        with AravisCamera(cfg(width=256, height=256)) as cam:
            cam.start()
            frames = [cam.grab() for _ in range(60)]
            cam.stop()
            stats = cam.statistics()
    finally:
        f.kill()
    ids = [fr.frame_id for fr in frames]
    assert all(b > a for a, b in itertools.pairwise(ids)), ids
    assert 0 <= stats.dropped <= ids[-1] - ids[0], stats
    assert ids[-1] == stats.completed + stats.failed + stats.dropped


def test_camera_killed_mid_stream_is_a_clear_error_with_stats_kept(fake: FakeGv) -> None:
    cam = AravisCamera(cfg())
    cam.open()
    cam.start()
    for _ in range(5):
        cam.grab()
    fake.kill()
    t0 = time.monotonic()
    with pytest.raises(CameraLost, match=r"lost .*reconnect is off.*\d+ completed") as lost:
        for _ in range(50):  # frames already in flight may still arrive
            cam.grab(timeout_ms=200)
    assert time.monotonic() - t0 < 10
    completed = cam.statistics().completed
    assert completed >= 5 and f"{completed} completed" in str(lost.value)  # the message carries the kept stats
    cam.close()  # safe after loss
    cam.close()


def test_reconnect_with_backoff_after_the_camera_comes_back(fake: FakeGv) -> None:
    cam = AravisCamera(cfg(reconnect=True, reconnect_attempts=6, reconnect_backoff_s=0.3))
    with cam:
        cam.start()
        cam.grab()
        fake.kill()
        threading.Timer(1.0, fake.start).start()
        frame = None
        for _ in range(100):
            try:
                frame = cam.grab(timeout_ms=300)
                if cam.statistics().reconnects:
                    break
            except CameraTimeout:
                continue
        stats = cam.statistics()
    assert stats.reconnects == 1 and frame is not None and stats.completed >= 2


def test_a_lost_device_is_released_with_no_handler_left_on_it(fake: FakeGv, monkeypatch) -> None:
    """The station died of SIGTRAP when a camera came back: the lost device's heartbeat thread read the new camera's
    control register, emitted control-lost for the driver's handler, and dropped the device's last reference at the
    end of that emission, so the device was finalised on its own heartbeat thread, which joined itself
    ('g_system_thread_wait: Resource deadlock avoided', a GLib error: SIGTRAP). With no handler left on a lost device
    GLib skips the emission, so no reference is taken there. The lost device's control-lost also marked the new
    connection lost."""
    from drivers import aravis_camera

    released: list[list[object]] = []
    monkeypatch.setattr(aravis_camera, "_release_in_background", lambda objects: released.append(list(objects)))
    with AravisCamera(cfg(reconnect=True, reconnect_attempts=6, reconnect_backoff_s=0.3)) as cam:
        cam.start()
        cam.grab()
        fake.kill()
        threading.Timer(1.0, fake.start).start()
        for _ in range(100):
            with contextlib.suppress(CameraTimeout):
                cam.grab(timeout_ms=300)
            if cam.statistics().reconnects:
                break
        assert cam.statistics().reconnects == 1
        from gi.repository import GObject

        devices = [o.get_device() for batch in released for o in batch if hasattr(o, "get_device")]
        assert devices, released
        for dev in devices:
            assert not GObject.signal_has_handler_pending(dev, GObject.signal_lookup("control-lost", dev), 0, False)
            dev.emit("control-lost")  # what the lost device's heartbeat does when the camera answers again
        assert not cam._lost.is_set()
        assert cam.grab(timeout_ms=2000).raw.shape == (48, 64)
        assert cam.statistics().reconnects == 1


def test_config_errors_name_the_feature() -> None:
    f = FakeGv().start()
    try:
        with pytest.raises(CameraConfigError, match=r"pixel_format 'Mono12p' not offered; .*Mono16"):
            AravisCamera(cfg(pixel_format="Mono12p")).open()
        with pytest.raises(CameraConfigError, match=r"gain_db = 30.0 outside the camera's range"):
            AravisCamera(cfg(gain_db=30.0)).open()
        with pytest.raises(CameraConfigError, match=r"'line2'.*Line0, Software"):
            AravisCamera(cfg(trigger="line2")).open()
    finally:
        f.kill()


def test_discovery_only_when_allowed(fake: FakeGv) -> None:
    with pytest.raises(CameraNotFound, match="GigE Vision discovery off"):
        AravisCamera(cfg(device=SERIAL)).open()
    assert [c.serial for c in list_cameras()] == []
    found = list_cameras(gige_discovery=True)
    assert [(c.serial, c.address) for c in found] == [(SERIAL, "127.0.0.1")]
    with AravisCamera(cfg(device=SERIAL), gige_discovery=True) as cam:
        cam.start()
        assert cam.grab().raw.shape == (48, 64)
    assert [c.serial for c in list_cameras(addresses=("127.0.0.1",))] == [SERIAL]


def test_station_cameras_command(fake: FakeGv, capsys: pytest.CaptureFixture[str]) -> None:
    from station.cli import main

    assert main(["cameras"]) == 1
    assert "GigE Vision discovery is off" in capsys.readouterr().out
    assert main(["cameras", "--gige-discovery"]) == 0
    assert SERIAL in capsys.readouterr().out
    assert main(["cameras", "--address", "127.0.0.1"]) == 0
    assert SERIAL in capsys.readouterr().out
