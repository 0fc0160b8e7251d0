"""The virtual camera served over GigE Vision (``drivers.gv_server``), received by ``AravisCamera`` on loopback.

Not collected by the default run: ``tests/drivers/test_gv_server.py`` runs this file with pytest inside a private
network namespace (loopback only), as the network rule requires. Run it alone the same way:
    unshare -n sh -c 'ip link set lo up &&
        exec .venv/bin/python -m pytest -o addopts= tests/drivers/netns/gv_server_cases.py'
"""

from __future__ import annotations

import json
import os
import signal
import socket
import sqlite3
import struct
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest

from drivers.aravis_camera import AravisCamera, list_cameras
from drivers.camera import CameraConfig
from drivers.errors import CameraConfigError, CameraError, CameraTimeout
from drivers.gv_server import GVCP_PORT, LUT_GAMMA, GvCameraServer, ServedTone, read_truth, toned
from drivers.netns import in_private_netns
from sim.dataset import DatasetSpec, Sample, init_dataset, open_dataset, split_of, write_sample
from sim.sensor import SensorConfig

pytestmark = pytest.mark.skipif(not in_private_netns(), reason="GigE Vision only inside a private network namespace")

W, H = 48, 32
DEFECTIVE = (1, 3, 5)
EMPTY = (6, 7)


def make_dataset(root: Path, n: int = 8, bit_depth: int = 8, empty: tuple[int, ...] = (), shift: int = 0) -> Path:
    """Tiny mosaics, distinct in every pixel; the sample index is encoded in pixel (0, 0) (and, scaled, in the
    rest), so a frame shows which part it is and any reordering of bytes shows too. ``empty``: samples that show
    no part (``"empty": true``, label 0). ``shift`` moves the other pixels' codes (8 bits): a twin set, the same
    parts seen by another camera."""
    init_dataset(root, DatasetSpec(width=W, height=H, sensor=SensorConfig(bit_depth=bit_depth)), n)
    y, x = np.mgrid[:H, :W]
    for i in range(n):
        if bit_depth == 8:
            raw = ((x + 3 * y + 17 * i + shift) % 256).astype(np.uint8)
        else:  # codes over 8 bits, up to full scale: byte order and bit depth both matter
            raw = ((x * 61 + y * 113 + 997 * i) % 2**bit_depth).astype(np.uint16)
        raw[0, 0] = i
        mask = np.zeros((H, W), bool)
        if i in DEFECTIVE:
            mask[4:8, 4:8] = True
        label = int(mask.any())
        params = {"index": i, "split": split_of(i), "label": label, "defect": {"type": "dent"} if label else None}
        write_sample(root, Sample(i, raw, params | ({"empty": True} if i in empty else {}), label, split_of(i),
                                  defect_mask=mask, object_mask=np.full((H, W), i not in empty)))
    return root


@pytest.fixture(scope="module")
def ds8(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return make_dataset(tmp_path_factory.mktemp("ds8"))


@pytest.fixture
def server(ds8: Path, tmp_path: Path) -> Iterator[GvCameraServer]:
    with GvCameraServer(str(ds8), defect_rate=0.5, truth_path=tmp_path / "truth.jsonl") as s:
        yield s


def cfg(**kw: object) -> CameraConfig:
    base = dict(device="127.0.0.1", pixel_format="Mono8", frame_rate_hz=200.0, trigger="free_run",
                timeout_ms=1000, reconnect=False, packet_size=1400)
    base.update(kw)
    return CameraConfig(**base)  # type: ignore[arg-type]


def mosaics(root: Path) -> dict[int, np.ndarray]:
    ds = open_dataset(root)
    return {i: ds.load(i, ground_truth=False).raw for i in ds.indices()}


def test_frames_are_the_datasets_mosaics_byte_for_byte(server: GvCameraServer, ds8: Path, tmp_path: Path) -> None:
    assert (server.address, server.width, server.height, server.pixel_format) == ("127.0.0.1", W, H, "Mono8")
    with AravisCamera(cfg()) as cam:
        cam.start()
        frames = [cam.grab() for _ in range(24)]
        cam.stop()
        stats = cam.statistics()
    server.close()  # flushes the truth file; frames sent after the last grab are recorded too
    truth = read_truth(tmp_path / "truth.jsonl")
    assert {r.timestamp_ns: r for r in server.recent} == truth
    raws = mosaics(ds8)
    for f in frames:
        rec = truth[f.timestamp_ns]  # the device timestamp is the join key
        assert f.raw.shape == (H, W) and f.raw.dtype == np.uint8 and f.bit_depth == 8 and f.pixel_format == "Mono8"
        assert f.raw.tobytes() == raws[rec.sample_index].tobytes()
        assert f.device_frame_id == rec.frame_id
        assert rec.label == (rec.sample_index in DEFECTIVE) and rec.split == split_of(rec.sample_index)
        assert rec.defect_type == ("dent" if rec.label else None)
    assert {truth[f.timestamp_ns].label for f in frames} == {0, 1}  # defect_rate 0.5 draws both kinds
    assert (stats.completed, stats.failed, stats.dropped) == (24, 0, 0)


def grab_raws(server: GvCameraServer, cam: AravisCamera, n: int) -> list[tuple[int, np.ndarray]]:
    """``n`` frames from a started ``cam`` -> [(sample index, raw)]."""
    cam.start()
    frames = [cam.grab() for _ in range(n)]
    cam.stop()
    truth = {r.timestamp_ns: r for r in server.recent}
    return [(truth[f.timestamp_ns].sample_index, f.raw) for f in frames]


def test_the_served_camera_bends_its_codes_while_its_tone_features_are_on(ds8: Path) -> None:
    """The rehearsal below is only worth something if the served camera applies what its features say."""
    raws = mosaics(ds8)
    with GvCameraServer(str(ds8)) as server, AravisCamera(cfg()) as cam:
        assert [round(cam._camera.get_float("Gamma"), 6), cam._camera.get_boolean("GammaEnable"),
                cam._camera.get_boolean("LUTEnable")] == [1.0, False, False]
        cam._camera.set_float("Gamma", 0.8)
        cam._camera.set_boolean("GammaEnable", True)
        for i, raw in grab_raws(server, cam, 4):
            assert raw.tobytes() == toned(raws[i], 255, 0.8).tobytes() != raws[i].tobytes()
        cam._camera.set_boolean("LUTEnable", True)
        for i, raw in grab_raws(server, cam, 4):
            assert raw.tobytes() == toned(toned(raws[i], 255, 0.8), 255, LUT_GAMMA).tobytes()


@pytest.mark.parametrize("tone", [ServedTone(gamma=0.8, gamma_enable=True, lut_enable=True),
                                  ServedTone(gamma=1.25, gamma_enable=None),
                                  ServedTone(gamma=0.8, gamma_enable=True, locked=("GammaEnable",))],
                         ids=["enable", "gamma-only", "enable-locked"])
def test_a_camera_left_with_a_tone_curve_is_set_linear_at_open(ds8: Path, tone: ServedTone) -> None:
    """Another tool left a gamma or a look-up table on: the codes were bent, and the shipped file, trained on
    linear codes, lost 5 points at gamma 0.8 (docs/results/2026-12-04-gamma.md). The driver turns GammaEnable
    off; where the camera has none, or it cannot be turned off, it sets Gamma 1."""
    raws = mosaics(ds8)
    with GvCameraServer(str(ds8), tone=tone) as server, AravisCamera(cfg()) as cam:
        assert not cam._camera.get_boolean("LUTEnable")
        for i, raw in grab_raws(server, cam, 6):
            assert raw.tobytes() == raws[i].tobytes()


ALL_TONE = ("Gamma", "GammaEnable", "LUTEnable")


@pytest.mark.parametrize("tone", [ServedTone(gamma=0.8, gamma_enable=True, locked=ALL_TONE),
                                  ServedTone(gamma=0.8, gamma_enable=None, locked=ALL_TONE),
                                  ServedTone(lut_enable=True, locked=ALL_TONE)],
                         ids=["GammaEnable", "Gamma", "LUTEnable"])
def test_a_camera_that_stays_non_linear_is_refused_naming_the_feature(ds8: Path, tone: ServedTone,
                                                                      request: pytest.FixtureRequest) -> None:
    feature = request.node.callspec.id
    with GvCameraServer(str(ds8), tone=tone), pytest.raises(CameraConfigError, match=rf"camera .*: {feature}\b"):
        AravisCamera(cfg()).open()


def test_a_linear_camera_whose_tone_features_are_read_only_opens(ds8: Path) -> None:
    """Nothing to change: a camera that is linear with its tone features locked is fine."""
    with GvCameraServer(str(ds8), tone=ServedTone(locked=ALL_TONE)), AravisCamera(cfg()) as cam:
        assert cam._camera is not None


def test_a_gamma_that_is_not_a_float_is_a_warning_not_a_refusal(ds8: Path, caplog: pytest.LogCaptureFixture) -> None:
    """Some cameras offer their gamma as an enumeration of curves: the driver cannot tell linear from not, so it says
    so and opens (refusing would leave such a camera unusable; the drift monitor still warns of a curve)."""
    with GvCameraServer(str(ds8), tone=ServedTone(gamma_enable=None, gamma_integer=True)), AravisCamera(cfg()) as cam:
        assert cam._camera is not None
    assert any("Gamma is not a number" in r.getMessage() for r in caplog.records)


def test_a_camera_that_comes_back_with_a_tone_curve_is_set_linear_again(ds8: Path) -> None:
    """A camera power-cycled mid-run loads its start-up user set, which may carry a gamma: the reconnect applies the
    configuration again, tone check included, so the frames after it are as linear as before."""
    raws = mosaics(ds8)
    server = GvCameraServer(str(ds8)).start()
    cam = AravisCamera(cfg(reconnect=True, reconnect_attempts=6, reconnect_backoff_s=0.3))
    try:
        with cam:
            cam.start()
            cam.grab()
            server.close()
            server = GvCameraServer(str(ds8), tone=ServedTone(gamma=0.8, gamma_enable=True, lut_enable=True)).start()
            after = []
            for _ in range(200):
                try:
                    frame = cam.grab(timeout_ms=300)
                except CameraTimeout:
                    continue
                if cam.statistics().reconnects:
                    after.append(frame)
                if len(after) == 4:
                    break
            assert cam.statistics().reconnects == 1 and len(after) == 4
            assert not cam._camera.get_boolean("GammaEnable") and not cam._camera.get_boolean("LUTEnable")
            truth = {r.timestamp_ns: r for r in server.recent}
            for f in after:
                assert f.raw.tobytes() == raws[truth[f.timestamp_ns].sample_index].tobytes()
    finally:
        server.close()


def test_empty_views_are_served_and_recorded_as_no_part(tmp_path: Path) -> None:
    ds = make_dataset(tmp_path / "ds", n=8, empty=EMPTY)
    with (GvCameraServer(str(ds), defect_rate=0.5, empty_rate=0.5, truth_path=tmp_path / "truth.jsonl"),
          AravisCamera(cfg()) as cam):
        cam.start()
        frames = [cam.grab() for _ in range(24)]
        cam.stop()
    truth = read_truth(tmp_path / "truth.jsonl")
    shown = [truth[f.timestamp_ns] for f in frames]
    assert all(r.present == (r.sample_index not in EMPTY) for r in shown)
    assert {r.present for r in shown} == {True, False}  # empty_rate 0.5 draws both
    assert all(r.label == 0 for r in shown if not r.present)
    assert all(f.raw[0, 0] == truth[f.timestamp_ns].sample_index for f in frames)


def test_12bit_set_is_served_as_mono12_and_other_formats_are_refused(tmp_path: Path) -> None:
    root = make_dataset(tmp_path / "ds12", bit_depth=12)
    raws = mosaics(root)
    with GvCameraServer(str(root), defect_rate=0.5) as server:
        assert server.pixel_format == "Mono12"
        with pytest.raises(CameraConfigError, match=r"pixel_format 'Mono8' not offered; the camera has Mono12$"):
            AravisCamera(cfg()).open()
        with AravisCamera(cfg(pixel_format="Mono12")) as cam:
            cam.start()
            frames = [cam.grab() for _ in range(6)]
        truth = {r.timestamp_ns: r for r in server.recent}
    for f in frames:
        assert f.raw.dtype == np.uint16 and f.bit_depth == 12 and f.raw.max() > 255
        np.testing.assert_array_equal(f.raw, raws[truth[f.timestamp_ns].sample_index])


def test_software_trigger_one_frame_per_trigger(server: GvCameraServer) -> None:
    with AravisCamera(cfg(trigger="software")) as cam:
        cam.start()
        with pytest.raises(CameraTimeout):
            cam.grab(timeout_ms=200)
        got = []
        for _ in range(3):
            t = time.monotonic()
            cam.trigger()
            got.append(cam.grab())
            assert time.monotonic() - t < 0.5
        with pytest.raises(CameraTimeout):
            cam.grab(timeout_ms=200)
    assert server.n_served == 3
    assert [f.timestamp_ns for f in got] == [r.timestamp_ns for r in server.recent]


def test_region_of_interest_is_cut_from_the_mosaic(server: GvCameraServer, ds8: Path) -> None:
    with AravisCamera(cfg(width=16, height=8, offset_x=4, offset_y=2)) as cam:
        cam.start()
        f = cam.grab()
    rec = {r.timestamp_ns: r for r in server.recent}[f.timestamp_ns]
    np.testing.assert_array_equal(f.raw, mosaics(ds8)[rec.sample_index][2:10, 4:20])


def test_only_loopback_unless_allowed(ds8: Path) -> None:
    with pytest.raises(CameraConfigError, match=r"'10\.1\.2\.3' is not a loopback interface.*--allow-network"):
        GvCameraServer(str(ds8), interface="10.1.2.3").start()
    with pytest.raises(CameraConfigError, match=r"no network interface 'eth7' \(have lo"):
        GvCameraServer(str(ds8), interface="eth7").start()
    # a second interface inside the namespace (a bridge: no traffic leaves the namespace)
    subprocess.run("ip link add pa-br0 type bridge && ip addr add 10.200.0.1/24 brd + dev pa-br0 && "
                   "ip link set pa-br0 up", shell=True, check=True)
    try:
        with pytest.raises(CameraConfigError, match="'pa-br0' is not a loopback interface"):
            GvCameraServer(str(ds8), interface="pa-br0").start()
        with GvCameraServer(str(ds8), interface="pa-br0", allow_network=True) as server:
            assert server.address == "10.200.0.1"
            # control only: as root, Aravis receives the stream on a packet socket bound to the interface, which
            # does not see this host's own traffic (it goes through lo)
            (info,) = list_cameras(addresses=("10.200.0.1",))
            assert (info.vendor, info.model, info.serial) == ("Polar-Ano", "VirtualPolarCamera", "POLARSIM1")
        # on loopback the device does not answer GigE Vision discovery broadcasts from another interface
        with GvCameraServer(str(ds8)), socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
            s.setsockopt(socket.SOL_SOCKET, socket.SO_BROADCAST, 1)
            s.bind(("10.200.0.1", 0))
            s.settimeout(0.3)
            discovery = struct.pack(">BBHHH", 0x42, 0x11, 0x0002, 0, 1)  # GVCP DISCOVERY_CMD, ack required
            s.sendto(discovery, ("255.255.255.255", GVCP_PORT))
            with pytest.raises(TimeoutError):
                s.recvfrom(1024)
            s.sendto(discovery, ("127.0.0.1", GVCP_PORT))  # unicast to its address: answered
            assert len(s.recvfrom(1024)[0]) > 8
    finally:
        subprocess.run(["ip", "link", "del", "pa-br0"], check=False)


def test_a_second_server_on_the_same_address_is_a_clear_error(server: GvCameraServer, ds8: Path) -> None:
    with pytest.raises(CameraError, match=r"cannot listen on 127\.0\.0\.1:3956: taken by another GigE Vision"):
        GvCameraServer(str(ds8)).start()


def test_two_served_cameras_give_each_part_its_two_frames(tmp_path: Path) -> None:
    """Two GigE cameras on two loopback addresses, the second serving the first's twin set (the same parts, the same
    draws): ``CameraPair`` over the real protocol, software-triggered, pairs each part's two frames."""
    from drivers.camera_pair import CameraPair

    line, side = make_dataset(tmp_path / "line"), make_dataset(tmp_path / "side", shift=101)
    seen = mosaics(side)
    with (two_servers(line, side, seed=5),
          CameraPair(AravisCamera(cfg(trigger="software")), AravisCamera(cfg(device="127.0.0.2", trigger="software")),
                     max_skew_ms=500.0) as pair):
        pair.start()
        got = []
        for _ in range(10):
            pair.trigger()
            got.append(pair.grab())
    assert len({int(f.raw[0, 0]) for f in got}) > 3  # parts in random order ...
    for f in got:  # ... each with its twin
        assert f.companion is not None and f.companion.raw.tobytes() == seen[int(f.raw[0, 0])].tobytes()
    assert pair.unpaired == 0 and pair.second_statistics().completed == 10


def aravis_config(tmp_path: Path, model: Path, camera: str = "", extra: str = "") -> Path:
    """``station.toml`` for ``station run --camera aravis`` on the camera served at 127.0.0.1 (``camera``: more
    ``[camera]`` lines; ``extra``: more tables): the simulated run's, with its ``[sim]`` table unused."""
    from tests.station.test_run import write_config

    return write_config(tmp_path, model, tmp_path / "unused", extra,
                        f'kind = "aravis"\ndevice = "127.0.0.1"\nreconnect = false\n{camera}')


def two_camera_config(tmp_path: Path, model: Path, second_model: Path, second: str = "") -> Path:
    """``aravis_config`` for two cameras, both software-triggered: the first at 127.0.0.1, the second
    (``[second_camera]``, judged by ``second_model``; ``second``: more of its lines, then any tables) at 127.0.0.2."""
    return aravis_config(tmp_path, model, 'trigger = "software"', f"""
[second_camera]
enabled = true
kind = "aravis"
device = "127.0.0.2"
trigger = "software"
reconnect = false
model = "{second_model}"
{second}
""")


@contextmanager
def two_servers(line: Path, side: Path, seed: int) -> Iterator[None]:
    """``line`` served at 127.0.0.1 and its twin ``side`` at 127.0.0.2 (added to loopback in this namespace), the
    same ``seed``, so both serve the same parts in the same order."""
    subprocess.run(["ip", "addr", "add", "127.0.0.2/8", "dev", "lo"], check=False, capture_output=True)
    with (GvCameraServer(str(line), defect_rate=0.5, seed=seed),
          GvCameraServer(str(side), defect_rate=0.5, seed=seed, interface="127.0.0.2", serial="POLARSIM2")):
        yield


def test_station_run_judges_two_served_cameras_as_one_part_each(tmp_path: Path) -> None:
    """A station with a second camera (``[second_camera]``) on two GigE Vision cameras, as a line would have them:
    ``station run --camera aravis``, both cameras software-triggered by the station, each frame judged by its own
    model. Every part gets one row with both cameras' scores and frame ids, decided on both thresholds."""
    pytest.importorskip("torch")
    from station.cli import main
    from tests.station.test_run import make_dataset as make_station_dataset
    from tests.station.test_run import make_model

    line, side = make_station_dataset(tmp_path / "line"), make_station_dataset(tmp_path / "side")
    model, side_model = make_model(tmp_path / "model" / "best"), make_model(tmp_path / "side" / "side")
    cfg = two_camera_config(tmp_path, model, side_model, 'threshold = 0.5\npresence_rule = "dolp_contrast"\n'
                                                         '[decision]\nthreshold = 0.9')
    with two_servers(line, side, seed=3):
        assert main(["run", "--camera", "aravis", "--config", str(cfg), "--frames", "5"]) == 0
    rows = sqlite3.connect(tmp_path / "log.sqlite").execute(
        "SELECT decision, score, threshold, second_score, second_threshold, camera_frame_id, second_frame_id, "
        "second_model_id, reason FROM inspections ORDER BY id").fetchall()
    assert len(rows) == 5
    for decision, score, thr, second, second_thr, frame_id, second_id, second_model, reason in rows:
        assert second is not None and second_id is not None and second_model.startswith("side-tiny-fused-"), reason
        assert (thr, second_thr) == (0.9, 0.5) and frame_id == second_id  # the nth frame of each camera
        assert decision == ("reject" if score > thr or second > second_thr else "pass"), reason
    # the untrained models score every part alike (0.548): the first camera passes it, the second rejects it
    assert {(r[0], r[8].split(" >")[0]) for r in rows} == {("reject", "second camera: score 0.5478")}


def test_station_capture_writes_two_served_cameras_frames_as_twin_folders(tmp_path: Path) -> None:
    """``station capture --second-out`` on two GigE Vision cameras: the same file name in both folders is the same
    part (pixel (0, 0) holds its index), and each folder holds its own camera's mosaic byte for byte."""
    pytest.importorskip("torch")
    import cv2

    from station.cli import main
    from tests.station.test_run import make_model

    line, side = make_dataset(tmp_path / "line"), make_dataset(tmp_path / "side", shift=101)
    model = make_model(tmp_path / "model" / "best")
    cfg = two_camera_config(tmp_path, model, model)
    out, side_out = tmp_path / "cap", tmp_path / "cap-side"
    with two_servers(line, side, seed=4):
        assert main(["capture", "--camera", "aravis", "--config", str(cfg), "--frames", "6", "--out", str(out),
                     "--second-out", str(side_out)]) == 0
    names = sorted(p.name for p in (out / "train" / "good").iterdir())
    assert names == sorted(p.name for p in (side_out / "train" / "good").iterdir()) and len(names) == 6
    raws = {"line": mosaics(line), "side": mosaics(side)}
    parts = set()
    for name in names:
        a, b = (cv2.imread(str(d / "train" / "good" / name), cv2.IMREAD_UNCHANGED) for d in (out, side_out))
        assert int(a[0, 0]) == int(b[0, 0])  # one part in both
        parts.add(int(a[0, 0]))
        assert a.tobytes() == raws["line"][int(a[0, 0])].tobytes()
        assert b.tobytes() == raws["side"][int(b[0, 0])].tobytes()
    assert len(parts) > 1


def serve_and_run(ds: Path, model: Path, tmp_path: Path, parts: int, camera: str = "") -> tuple[str, str]:
    """``station serve-camera --dataset ds`` in a subprocess, ``station run --camera aravis`` on it here for
    ``parts`` parts (``camera``: more ``[camera]`` lines); returns the server's banner and its whole output."""
    from station.cli import main

    server = subprocess.Popen([sys.executable, "-m", "station.cli", "serve-camera", "--dataset", str(ds),
                               "--defect-rate", "0.5", "--truth", str(tmp_path / "truth.jsonl")],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              cwd=Path(__file__).parents[3], env={**os.environ, "PYTHONUNBUFFERED": "1"})
    banner = ""
    try:
        assert server.stdout is not None
        while "station.toml:" not in banner:  # up once it has printed the config line
            line = server.stdout.readline()
            assert line, f"serve-camera ended: {banner}"
            banner += line
        cfg_path = aravis_config(tmp_path, model, camera)
        assert main(["run", "--camera", "aravis", "--config", str(cfg_path), "--frames", str(parts)]) == 0
    finally:
        server.send_signal(signal.SIGTERM)
        out, _ = server.communicate(timeout=20)
    assert server.returncode == 0, out
    return banner, out


@pytest.mark.slow  # ~8 s on 2 busy cores: torch, a model warm-up and a second process
def test_station_run_inspects_the_served_camera_end_to_end(tmp_path: Path) -> None:
    """``station serve-camera`` in a subprocess, ``station run --camera aravis`` here; the log joins the truth."""
    pytest.importorskip("torch")
    from tests.station.test_run import make_dataset as make_station_dataset
    from tests.station.test_run import make_model

    ds = make_station_dataset(tmp_path / "ds")
    model = make_model(tmp_path / "model" / "best")
    truth = tmp_path / "truth.jsonl"
    banner, out = serve_and_run(ds, model, tmp_path, 6)
    assert 'device = "127.0.0.1", pixel_format = "Mono8"' in banner
    assert "served" in out and "frames" in out
    rows = sqlite3.connect(tmp_path / "log.sqlite").execute(
        "SELECT decision, camera_timestamp_ns FROM inspections ORDER BY id").fetchall()
    served = read_truth(truth)
    assert len(rows) == 6 and all(d in ("pass", "reject") for d, _ in rows)
    assert all(ts in served for _, ts in rows)  # every inspected part is scored against its ground truth
    assert len(served) == len(truth.read_text().splitlines()) >= 6
    assert all(json.loads(line)["sample_index"] in range(10) for line in truth.read_text().splitlines())


def test_a_segment_set_is_served_a_parts_frames_in_turn(tmp_path: Path) -> None:
    """A set with a frame per dome segment: each software trigger gets the part's next frame, in the segments'
    order, over the real protocol; the station triggers each (``[camera] dome_segments``)."""
    from sim.scene import SceneConfig

    root = tmp_path / "pair"
    init_dataset(root, DatasetSpec(width=W, height=H, dome_segments=(0.0, 180.0),
                                   scene=SceneConfig(ambient_gradient=0.8)), 6)
    y, x = np.mgrid[:H, :W]
    for i in range(6):  # pixel (0, 0): the sample; (0, 1): the frame
        raws = tuple(((x + 3 * y + 17 * i + 101 * k) % 256).astype(np.uint8) for k in range(2))
        for k, raw in enumerate(raws):
            raw[0, 0], raw[0, 1] = i, k
        label = int(i in DEFECTIVE)
        write_sample(root, Sample(i, raws[0], {"index": i, "split": split_of(i), "label": label,
                                               "defect": {"type": "dent"} if label else None}, label, split_of(i),
                                  defect_mask=np.zeros((H, W), bool), segment_raws=raws))
    sets = {i: open_dataset(root).load(i, ground_truth=False).raws for i in range(6)}
    with GvCameraServer(str(root), defect_rate=0.5) as server, AravisCamera(cfg(trigger="software")) as cam:
        cam.start()
        got = []
        for _ in range(8):
            cam.trigger()
            got.append(cam.grab())
        truth = {r.timestamp_ns: r for r in server.recent}
    for first, second in zip(got[::2], got[1::2], strict=True):
        index = truth[first.timestamp_ns].sample_index
        assert truth[second.timestamp_ns].sample_index == index
        assert first.raw.tobytes() == sets[index][0].tobytes() and second.raw.tobytes() == sets[index][1].tobytes()


@pytest.mark.slow  # ~10 s: torch, a model warm-up and a second process
def test_station_run_takes_a_served_segment_set_part_by_part(tmp_path: Path) -> None:
    """``station serve-camera`` of a set with a frame per dome segment, ``station run --camera aravis`` with
    ``[camera] dome_segments``: each part's two frames over the real protocol, one row per part."""
    torch = pytest.importorskip("torch")
    from model.draem.checkpoint import save_checkpoint
    from model.draem.config import ModelConfig
    from model.draem.detector import Detector
    from tests.station.line_sets import make_segment_set

    ds = make_segment_set(tmp_path / "pair", n=8)
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "tilt_x"), "fused", 32, "center",
                                           dome_segments=(0.0, 180.0)))
    det.init_weights(torch.Generator().manual_seed(0))
    model = tmp_path / "model" / "best"
    save_checkpoint(model, det, threshold=0.5, threshold_rule="test")
    serve_and_run(ds, model, tmp_path, 5, camera="dome_segments = [0.0, 180.0]")
    served = {r.timestamp_ns: r for r in read_truth(tmp_path / "truth.jsonl").values()}
    order = sorted(served.values(), key=lambda r: r.timestamp_ns)
    rows = sqlite3.connect(tmp_path / "log.sqlite").execute(
        "SELECT decision, camera_timestamp_ns FROM inspections ORDER BY id").fetchall()
    assert len(rows) == 5 and all(d in ("pass", "reject") for d, _ in rows)
    for _, ts in rows:  # each row's first frame, then the same part's second frame, sent next
        k = next(j for j, r in enumerate(order) if r.timestamp_ns == ts)
        assert order[k + 1].sample_index == order[k].sample_index
