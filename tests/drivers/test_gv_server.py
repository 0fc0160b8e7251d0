"""The virtual camera served as a GigE Vision device (``drivers.gv_server``, ``station serve-camera``).

The GigE Vision cases live in ``netns/gv_server_cases.py``; this test runs them with pytest in a fresh namespace
that has only loopback (the network rule). What needs no socket runs here.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from drivers.errors import CameraConfigError
from drivers.gv_server import ServedTone, _genicam_xml, is_loopback_interface, toned
from drivers.netns import netns_command, netns_unavailable_reason
from station.cli import main

CASES = Path(__file__).parent / "netns" / "gv_server_cases.py"


def run_cases(marker: str) -> None:
    """Run the cases selected by ``-m marker`` in a private network namespace; every one must pass."""
    reason = netns_unavailable_reason()
    if reason:
        pytest.skip(f"no private network namespace: {reason}")
    argv = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-o", "addopts=", "-m", marker,
            str(CASES)]
    r = subprocess.run(netns_command(argv), capture_output=True, text=True, timeout=240,
                       cwd=Path(__file__).parents[2])
    print(r.stdout[-5000:])
    assert r.returncode == 0, r.stdout[-8000:] + r.stderr[-3000:]
    assert " passed" in r.stdout and "skipped" not in r.stdout


def test_gv_server_over_gige_vision_in_private_namespace() -> None:
    run_cases("not slow")


@pytest.mark.slow
def test_station_run_over_gige_vision_in_private_namespace() -> None:
    run_cases("slow")


def test_loopback_is_told_by_flag_or_address() -> None:
    assert is_loopback_interface("lo") and is_loopback_interface("127.0.0.1")
    assert not is_loopback_interface("192.168.10.20")
    with pytest.raises(CameraConfigError, match="no network interface 'no-such-if0'"):
        is_loopback_interface("no-such-if0")


def test_genicam_xml_offers_only_the_served_format() -> None:
    base = ('<Enumeration Name="PixelFormat" NameSpace="Standard">\n<DisplayName>Pixel format</DisplayName>\n'
            '<EnumEntry Name="Mono8" NameSpace="Standard"><Value>17301505</Value></EnumEntry>\n'
            '<EnumEntry Name="Mono16" NameSpace="Standard"><Value>17825799</Value></EnumEntry>\n'
            '<pValue>PixelFormatRegister</pValue>\n</Enumeration><EnumEntry Name="Other"/>')
    xml = _genicam_xml(base, "Mono12", 0x01100005)
    assert xml.count("<EnumEntry") == 2 and 'Name="Mono12"' in xml and "<Value>17825797</Value>" in xml
    assert "Mono16" not in xml and 'Name="Mono8"' not in xml and xml.endswith('<EnumEntry Name="Other"/>')


def test_serve_camera_refuses_a_network_interface(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # refused before any socket is opened: safe outside a namespace
    assert main(["serve-camera", "--dataset", str(tmp_path), "--interface", "192.168.10.20"]) == 2
    err = capsys.readouterr().err
    assert "station serve-camera: error:" in err and "not a loopback interface" in err and "--allow-network" in err


def test_a_served_tone_curve_keeps_black_and_full_scale_and_bends_between() -> None:
    codes = np.array([0, 64, 512, 4095], np.uint16)
    assert toned(codes, 4095, 1.0) is codes
    bent = toned(codes, 4095, 0.8)
    assert bent.dtype == np.uint16 and bent[0] == 0 and bent[-1] == 4095
    assert list(bent[1:3]) == [round(4095 * (64 / 4095) ** 0.8), round(4095 * (512 / 4095) ** 0.8)]


def test_genicam_xml_offers_the_tone_features_and_locks_those_named() -> None:
    base = ('<Enumeration Name="PixelFormat"><EnumEntry Name="Mono8"><Value>1</Value></EnumEntry>'
            "<pValue>P</pValue></Enumeration></RegisterDescription>")
    free = _genicam_xml(base, "Mono8", 1, ServedTone())
    assert all(f'Name="{f}" NameSpace="Standard"' in free for f in ("Gamma", "GammaEnable", "LUTEnable"))
    assert "SwissKnife" not in free and free.endswith("</RegisterDescription>")
    locked = _genicam_xml(base, "Mono8", 1, ServedTone(gamma_enable=None, locked=("Gamma",)))
    assert "<pValue>GammaLocked</pValue>" in locked and "<pValue>LUTEnableRegister</pValue>" in locked
    assert 'Name="GammaEnable"' not in locked


def test_serve_camera_refuses_a_gamma_out_of_range(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["serve-camera", "--dataset", str(tmp_path), "--gamma", "5"]) == 2
    assert "tone gamma 5.0: must be within [0.25, 4]" in capsys.readouterr().err
