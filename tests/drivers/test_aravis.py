"""The Aravis driver against Aravis's own GigE Vision fake camera, inside a private network namespace.

The cases live in ``netns/aravis_cases.py``; this test runs them with pytest in a fresh namespace that has only
loopback (the network rule: GigE Vision discovery and the fake camera never touch a real network).
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from drivers.netns import netns_command, netns_unavailable_reason

CASES = Path(__file__).parent / "netns" / "aravis_cases.py"


def test_aravis_driver_over_gige_vision_in_private_namespace() -> None:
    reason = netns_unavailable_reason()
    if reason:
        pytest.skip(f"no private network namespace: {reason}")
    if shutil.which("arv-fake-gv-camera-0.8") is None:
        pytest.skip("arv-fake-gv-camera-0.8 not installed (Debian package aravis-tools)")
    argv = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-o", "addopts=", str(CASES)]
    r = subprocess.run(netns_command(argv), capture_output=True, text=True, timeout=240,
                       cwd=Path(__file__).parents[2])
    print(r.stdout[-5000:])
    assert r.returncode == 0, r.stdout[-8000:] + r.stderr[-3000:]
    assert " passed" in r.stdout and "skipped" not in r.stdout


def test_a_software_trigger_that_fails_again_after_a_reconnect_is_a_driver_error(monkeypatch) -> None:
    """The retry after a reconnect let GLib.Error escape (a traceback in station capture). No device is opened."""
    pytest.importorskip("gi")
    from drivers.aravis_camera import AravisCamera, _aravis
    from drivers.camera import CameraConfig
    from drivers.errors import TriggerFailed

    _, GLib, _ = _aravis()

    class Flaky:  # answers the reconnect, then times out on the command again
        def software_trigger(self) -> None:
            raise GLib.Error("GVCP timeout")

    cam = AravisCamera(CameraConfig(device="127.0.0.1", trigger="software"))
    cam._camera, cam._started = Flaky(), True
    monkeypatch.setattr(cam, "_handle_loss", lambda why: setattr(cam, "_camera", Flaky()))
    with pytest.raises(TriggerFailed, match="software trigger"):
        cam.trigger()


@pytest.mark.parametrize("address", ["255.255.255.255", "224.0.0.1", "0.0.0.0", "239.255.255.250"])
def test_a_broadcast_or_multicast_camera_address_is_refused_before_anything_is_sent(address: str) -> None:
    """`station cameras --address 255.255.255.255` tried to send (the sandbox refused it): a broadcast or multicast
    address is discovery by another name, which the network rule keeps off every interface."""
    pytest.importorskip("gi")
    from drivers.aravis_camera import _open_gv_device
    from drivers.errors import CameraConfigError

    with pytest.raises(CameraConfigError, match="not a single camera's address"):
        _open_gv_device(address)
