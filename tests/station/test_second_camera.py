"""A station with a second camera: one answer and one true row per part, a reject by either camera rejects, and any
fault of the second camera rejects the part (fail closed)."""

from __future__ import annotations

import dataclasses
import json
import threading
import time

import numpy as np
import pytest

from drivers.camera_pair import CameraPair
from drivers.errors import CameraTimeout
from model.priors import IMX250MZR
from station.cli import main
from station.config import ConfigError, parse_config
from station.decision import Decision, Verdict, join
from station.inspection_log import InspectionLog
from station.inspector import Inference, Inspector
from station.loop import Station
from station.presence import Presence, PresenceRule
from station.reject_store import RejectStore
from station.second_camera import PairInspector
from tests.station.test_loop import BrightnessDetector, ScriptedCamera, ScriptedLink

PASS, REJECT, EMPTY = Decision(Verdict.PASS), Decision(Verdict.REJECT, "score 0.9 > threshold 0.5"), \
    Decision(Verdict.EMPTY, "no part in view: x")


@pytest.mark.parametrize(("first", "second", "verdict", "reason"), [
    (PASS, PASS, Verdict.PASS, None),
    (REJECT, PASS, Verdict.REJECT, "score 0.9 > threshold 0.5"),
    (PASS, REJECT, Verdict.REJECT, "side: score 0.9 > threshold 0.5"),
    (REJECT, REJECT, Verdict.REJECT, "score 0.9 > threshold 0.5; side: score 0.9"),
    (EMPTY, EMPTY, Verdict.EMPTY, "no part in view: x; side: no part in view: x"),
    (EMPTY, PASS, Verdict.REJECT, "not judged: the first camera sees no part (no part in view: x), the side sees one"),
    (PASS, EMPTY, Verdict.REJECT, "not judged: the side sees no part (no part in view: x), the first camera sees one"),
    (EMPTY, REJECT, Verdict.REJECT, "side: score 0.9"),
])
def test_two_cameras_decisions_join_failing_closed(first, second, verdict, reason):
    joined = join(first, second, "side")
    assert joined.decision == verdict
    assert joined.reason == reason if reason is None else joined.reason.startswith(reason)


class DarkIsEmpty:
    """A presence check for the scripted frames: a frame darker than 10 codes shows no part."""

    priors = ("intensity",)

    def __call__(self, priors):
        level = float(priors["intensity"].mean())
        return Presence(level >= 10 / 255, level, 10 / 255, PresenceRule.ROW_CONTRAST)


class SideCamera(ScriptedCamera):
    """``ScriptedCamera`` whose 'dark' entries are black frames (no part in view)."""

    def next_item(self):
        self.last = super().next_item()
        return self.last

    def grab(self, timeout_ms=None):
        frame = super().grab(timeout_ms)
        return dataclasses.replace(frame, raw=np.zeros_like(frame.raw)) if self.last == "dark" else frame


class SecondDetector(BrightnessDetector):
    model_id = "test-side"
    threshold = 0.6


def two_camera_station(tmp_path, first, second, n, second_detector=None, first_detector=None, parallel=True,
                       **monitors):
    """``n`` announced parts; items 0/1 are good/defective as each camera sees the part, 'dark' no part in view;
    ``monitors``: the station's ``drift`` and ``second_drift``."""
    log = InspectionLog(tmp_path / "log.sqlite")
    rejects = RejectStore(tmp_path / "rejects")
    link = ScriptedLink(n, log=log)
    pair = CameraPair(ScriptedCamera(first, trigger="software"), SideCamera(second, trigger="software"),
                      max_skew_ms=1000.0)
    inspector = PairInspector(Inspector(first_detector or BrightnessDetector(), IMX250MZR, statistics=True),
                              Inspector(second_detector or SecondDetector(), IMX250MZR, presence=DarkIsEmpty(),
                                        statistics=True), parallel)
    station = Station(pair, inspector, link, log, cycle_time_ms=10_000.0, queue_size=16, backpressure="block",
                      rejects=rejects, **monitors)
    return station, link, log


def test_a_part_only_the_second_camera_finds_defective_is_rejected_and_its_row_says_which(tmp_path):
    station, link, log = two_camera_station(tmp_path, [0, 0, 1, 1], [0, 1, 0, 1], 4)
    station.run(max_parts=4)
    rows = list(log.rows())
    assert [r["decision"] for r in rows] == ["pass", "reject", "reject", "reject"]
    assert dict(link.reports) == {"T0": "pass", "T1": "reject", "T2": "reject", "T3": "reject"}
    assert rows[1]["reason"].startswith("second camera: score 1.5686 > threshold 0.6000")
    assert rows[2]["reason"].startswith("score 1.5686 > threshold 0.5000") and "second camera" not in rows[2]["reason"]
    assert "; second camera: score" in rows[3]["reason"]
    for r in rows:
        assert r["model_id"] == "test-brightness" and r["threshold"] == 0.5
        assert r["second_model_id"] == "test-side" and r["second_threshold"] == 0.6
        assert r["second_frame_id"] == r["camera_frame_id"]
    assert [round(r["second_score"], 4) for r in rows] == [0.1569, 1.5686, 0.1569, 1.5686]
    with np.load(rows[1]["image_path"]) as kept:  # a rejected part's image file holds both cameras' frames
        assert set(kept) == {"raw", "second_raw"} and kept["second_raw"].mean() > kept["raw"].mean()
    # a defect only the second camera sees is a defective part's (part T1)
    assert [r["ground_truth_label"] for r in rows] == [0, 1, 1, 1]
    assert station.stats.confusion == {"good_pass": 1, "bad_reject": 3}


def test_the_second_camera_is_watched_against_its_own_model_and_its_warnings_name_it(tmp_path, caplog):
    """The side camera's light dims while the first camera's stays: the second camera's drift monitor warns once,
    naming it and its own keys, the warning stays in each row's ``drift``, and no decision is made from it. Parts
    partly outside the second model's view do not warn (``station.drift.CameraWatch`` says why)."""
    from model.priors.frame_stats import FrameStatistics, StatisticsRange
    from station.drift import DriftMonitor

    class Turned(SecondDetector):
        """The second model: every third part partly outside its view."""

        calls = 0

        def infer(self, priors):
            Turned.calls += 1
            return Inference(super().infer(priors).score, checks={"unseen_fraction": 0.01 * (Turned.calls % 3 == 0)})

    bright = StatisticsRange.from_frames(FrameStatistics(0.78 + 0.01 * (i % 3), 0.785, 0.0, 0.0) for i in range(30))
    dim = StatisticsRange.from_frames(FrameStatistics(0.078 + 0.001 * (i % 3), 0.0785, 0.0, 0.0) for i in range(30))
    n = 30
    station, link, log = two_camera_station(
        tmp_path, [0] * n, [1] * 10 + [0] * 20, n, Turned(),
        drift=DriftMonitor(dim, window=10, min_frames=5),  # the first camera's frames: code 20, as trained
        second_drift=DriftMonitor(bright, window=10, min_frames=5, section="second_camera"))
    station.run(max_parts=n)
    rows = list(log.rows())
    assert len(rows) == n and len(link.reports) == n
    assert all(r["drift"] is None for r in rows[:14])  # 10 frames as trained, then 4 of 10 dim: the median holds
    assert all(r["drift"].startswith("second camera: drift over the last 10 frames: median_level") and
               "raise [second_camera] exposure_us" in r["drift"] for r in rows[14:])
    assert not any("view" in r["drift"] for r in rows[14:])  # 10 of 30 parts partly outside its view: not watched
    warned = [r.message for r in caplog.records if "second camera: " in r.message]
    assert len(warned) == 1 and warned[0].startswith("second camera: drift")
    assert not any(r.message.startswith("drift over") for r in caplog.records)  # the first camera: in range
    assert [r["decision"] for r in rows] == ["reject"] * 10 + ["pass"] * 20  # by the scores alone


def test_any_fault_of_the_second_camera_rejects_the_part(tmp_path):
    # part T1: the second camera gives no frame; T2: it sees no part where the first camera sees one
    station, link, log = two_camera_station(tmp_path, [0, 0, 0, 0], [0, CameraTimeout("no frame in 5 ms"), "dark", 0],
                                            4)
    station.run(max_parts=4)
    rows = {r["part_id"]: r for r in log.rows()}
    assert len(rows) == 4 and dict(link.reports) == {"T0": "pass", "T1": "reject", "T2": "reject", "T3": "pass"}
    assert "no frame for part T1: second camera: no frame in 5 ms" in rows["T1"]["reason"]
    assert rows["T1"]["second_score"] is None and rows["T1"]["second_frame_id"] is None
    assert rows["T2"]["reason"].startswith("not judged: the second camera sees no part (no part in view")
    assert rows["T2"]["second_score"] is None  # its model did not run


def test_a_failing_second_model_rejects_the_part(tmp_path):
    station, link, log = two_camera_station(tmp_path, [0, 0], [0, 0], 2, SecondDetector(fail=True))
    station.run(max_parts=2)
    rows = list(log.rows())
    assert [r["decision"] for r in rows] == ["reject", "reject"] and set(dict(link.reports).values()) == {"reject"}
    assert all(r["reason"].startswith("second camera: not judged: frame") and "weights corrupt" in r["reason"]
               for r in rows)


def test_the_second_cameras_thread_ends_with_the_run_and_a_second_run_gets_a_new_one(tmp_path):
    # Threads are told apart by identity, not counted: an earlier test's pool thread may still be ending when this
    # test starts (seen under load in a clean-clone run: counted, it ended mid-test and the count fell below).
    earlier = {t for t in threading.enumerate() if t.name.startswith("second-camera")}

    def second_threads_left_by_the_run():  # an idle pool's thread ends moments after the pool is shut down
        deadline = time.monotonic() + 2.0
        while (left := [t for t in threading.enumerate() if t.name.startswith("second-camera") and t not in earlier]) \
                and time.monotonic() < deadline:
            time.sleep(0.01)
        return left

    station, _, log = two_camera_station(tmp_path, [0, 1], [0, 0], 2)
    station.run(max_parts=1)
    assert second_threads_left_by_the_run() == []  # PairInspector.close(): its pool's thread ends with the run
    station.run(max_parts=1)  # the same station runs again: the pool is made anew
    assert second_threads_left_by_the_run() == []
    assert [r["decision"] for r in log.rows()] == ["pass", "reject"]


@pytest.mark.parametrize("parallel", [True, False])
def test_both_cameras_time_their_stages_in_the_row(tmp_path, parallel):
    station, _, log = two_camera_station(tmp_path, [0], [0], 1, SecondDetector(delay_s=0.1),
                                         BrightnessDetector(delay_s=0.1), parallel)
    station.run(max_parts=1)
    (row,) = log.rows()
    assert row["decision"] == "pass"
    if parallel:  # the two models at the same time: the part takes about one model's time
        assert 100.0 <= row["model_ms"] < 190.0 and row["total_ms"] < 190.0
    else:  # one after the other: both
        assert row["model_ms"] >= 200.0 and row["total_ms"] >= 200.0


def test_station_run_with_a_virtual_second_camera_showing_the_same_parts(tmp_path, capsys):
    from tests.station.test_run import make_dataset, make_model, write_config

    model, side = make_model(tmp_path / "model" / "best"), make_model(tmp_path / "side" / "side")
    ds, twin = make_dataset(tmp_path / "ds"), make_dataset(tmp_path / "twin")
    cfg = write_config(tmp_path, model, ds, f'[second_camera]\nenabled = true\nmodel = "{side}"\ndataset = "{twin}"\n'
                                            'threshold = 0.55\nframe_rate_hz = 20.0\npresence_rule = "dolp_contrast"\n')
    assert main(["run", "--camera", "sim", "--config", str(cfg), "--frames", "6",
                 "--summary-json", str(tmp_path / "s.json")]) == 0
    assert "second camera's model side-tiny-fused" in capsys.readouterr().out
    rows = list(InspectionLog(tmp_path / "log.sqlite", readonly=True).rows())
    assert len(rows) == 6
    for r in rows:
        assert r["second_model_id"].startswith("side-tiny-fused-") and r["second_threshold"] == 0.55
        assert r["second_frame_id"] == r["camera_frame_id"] and r["io_delivered"] == 1
        assert (r["decision"] == "reject") == (r["score"] > 0.5 or r["second_score"] > 0.55)
    summary = json.loads((tmp_path / "s.json").read_text())
    assert summary["camera"]["second_camera"]["completed"] == 6 and summary["camera"]["second_camera"]["unpaired"] == 0


def test_station_run_watches_the_second_camera_against_the_frames_its_own_model_records(tmp_path, capsys):
    """``station run`` builds the second camera's drift monitor from its model's recorded frame statistics: frames
    darker than those warn, named for the second camera and its keys; the first model records none (no check)."""
    import torch

    from model.draem.checkpoint import save_checkpoint
    from model.draem.config import ModelConfig
    from model.draem.detector import Detector
    from model.priors.frame_stats import FrameStatistics, StatisticsRange
    from tests.station.test_run import make_dataset, make_model, write_config

    side = tmp_path / "side" / "side"
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "fused", 32, "center"))
    det.init_weights(torch.Generator().manual_seed(0))
    brighter = StatisticsRange.from_frames(FrameStatistics(0.97 + 0.005 * (i % 3), 0.99, 0.0, 0.1) for i in range(9))
    save_checkpoint(side, det, threshold=0.5, threshold_rule="test", train={"frame_statistics": brighter.to_dict()})
    model, ds = make_model(tmp_path / "model" / "best"), make_dataset(tmp_path / "ds")
    twin = make_dataset(tmp_path / "twin")
    cfg = write_config(tmp_path, model, ds, f'[second_camera]\nenabled = true\nmodel = "{side}"\ndataset = "{twin}"\n'
                                            'frame_rate_hz = 20.0\npresence_rule = "dolp_contrast"\n')
    assert main(["run", "--camera", "sim", "--config", str(cfg), "--frames", "12"]) == 0
    rows = list(InspectionLog(tmp_path / "log.sqlite", readonly=True).rows())
    assert len(rows) == 12 and all(r["drift"] is None for r in rows[:9])  # 10 frames before the median is read
    assert all(r["drift"].startswith("second camera: drift over the last") and "median_level" in r["drift"] and
               "[second_camera] exposure_us" in r["drift"] for r in rows[9:])


def test_a_twin_set_of_other_parts_stops_the_station_before_the_first_part(tmp_path, capsys):
    from tests.station.test_run import make_dataset, make_model, write_config

    model = make_model(tmp_path / "model" / "best")
    ds, twin = make_dataset(tmp_path / "ds"), make_dataset(tmp_path / "twin", defective=lambda i: i % 2 == 0)
    cfg = write_config(tmp_path, model, ds, f'[second_camera]\nenabled = true\nmodel = "{model}"\n'
                                            f'dataset = "{twin}"\n')
    assert main(["run", "--config", str(cfg), "--frames", "2"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "not a twin set" in err[0], err
    assert not list(InspectionLog(tmp_path / "log.sqlite", readonly=True).rows())


@pytest.mark.parametrize(("text", "message"), [
    ("enabled = true", r"\[second_camera\] model: must name"),
    ('enabled = true\nmodel = "m"\nkind = "aravis"', r"\[second_camera\] kind: 'aravis', but \[camera\] kind is 'sim'"),
    ('enabled = true\nmodel = "m"', r"\[second_camera\] dataset: the virtual second camera needs its twin"),
    ('enabled = true\nmodel = "m"\ndataset = "d"\ndome_segments = [0, 180]', "one frame per part"),
    ('enabled = true\nmodel = "m"\ndataset = "d"\ntrigger = "line0"', r"trigger: 'line0' with \[camera\] trigger"),
    ('enabled = true\nmodel = "m"\ndataset = "d"\nexposure_us = 90000\ntimeout_ms = 100', "timeout_ms: 100 ms"),
    ('presence_rule = "magic"', r"presence_rule: 'magic' is not one of"),
])
def test_bad_second_camera_keys_name_the_key(text, message):
    with pytest.raises(ConfigError, match=message):
        parse_config(f'[sim]\ndataset = "s"\n[second_camera]\n{text}\n', "station.toml")


def test_station_split_sets_both_thresholds_within_one_budget(tmp_path, capsys):
    from tests.station.test_run import make_dataset, make_model

    model, side = make_model(tmp_path / "model" / "best"), make_model(tmp_path / "side" / "side", ("intensity",))
    ds, twin = make_dataset(tmp_path / "ds", n=30), make_dataset(tmp_path / "twin", n=30)
    args = ["split", "--model", str(model), "--data", str(ds), "--second-model", str(side), "--second-data", str(twin),
            "--split", "train", "--second-presence-rule", "dolp_contrast", "--max-good-flagged", "0.25"]
    assert main([*args, "--budget", "count", "--out", str(tmp_path / "split.json")]) == 0
    out = capsys.readouterr().out
    report = json.loads((tmp_path / "split.json").read_text())
    assert report["parts"] == 21 and report["good"] == 9 and report["budget"] == 2
    assert [r["k"] for r in report["splits"]] == [0, 1, 2]
    assert all(r["good_rejected"] <= 2 for r in report["splits"])
    chosen = report["splits"][report["chosen"]]
    assert chosen["caught"] == max(r["caught"] for r in report["splits"])
    from station.commands.split import config_number

    assert out.count("<- chosen") == 1 and f"[second_camera]\nthreshold = {config_number(chosen['second'])}" in out
    assert f"[decision]\nthreshold = {config_number(chosen['first'])}" in out
    above = report["chosen_good_above"]
    assert above["first"] + above["second"] >= chosen["good_rejected"] >= max(above.values())
    assert (f"chosen split: {chosen['good_rejected']} of {report['good']} good parts rejected (first camera "
            f"{above['first']}, second {above['second']}); new good parts: at most about ") in out
    # the default budget holds 25 % of new good parts on average: floor(0.25 x 10) - 2 = 0 of the 9 good parts
    assert main([*args, "--out", str(tmp_path / "expected.json")]) == 0
    expected = json.loads((tmp_path / "expected.json").read_text())
    assert expected["budget"] == 0 and expected["expected"] and [r["good_rejected"] for r in expected["splits"]] == [0]
    assert "budget 0 good parts (25 % of new good parts on average)" in capsys.readouterr().out
    assert main([*args[:-1], "0.1"]) == 2  # 9 good parts cannot hold 10 % for two cameras
    assert "9 good parts cannot hold 10.00% of new good parts rejected by 2 cameras on average: that needs 19 or " \
           "more" in capsys.readouterr().err.splitlines()[-1]
    other = make_dataset(tmp_path / "other", n=30)
    for f in (other / "samples").glob("*/params.json"):  # the same parts with another defect
        params = json.loads(f.read_text())
        if params["defect"]:
            f.write_text(json.dumps({**params, "defect": {"type": "dent"}}))
    assert main([*args[:8], str(other), *args[9:]]) == 2
    err = capsys.readouterr().err
    assert "are not twin sets: sample 3 shows a stain in one and a dent in the other" in err.splitlines()[-1]
    assert "Traceback" not in err


def test_station_split_pools_several_twin_sets_and_writes_each_parts_scores(tmp_path, capsys):
    """725 good twins allow a budget of 5 where 368 allow 1 (rule 64): ``station split`` takes several twin pairs,
    counts every part once, and refuses a set named twice (its parts would count twice)."""
    from tests.station.test_run import make_dataset, make_model

    model, side = make_model(tmp_path / "model" / "best"), make_model(tmp_path / "side" / "side", ("intensity",))
    pairs = [(make_dataset(tmp_path / f"ds{j}", n=30), make_dataset(tmp_path / f"twin{j}", n=30)) for j in (0, 1)]
    base = ["split", "--model", str(model), "--second-model", str(side), "--split", "train",
            "--second-presence-rule", "dolp_contrast", "--max-good-flagged", "0.25", "--budget", "count"]
    both_sets = ["--data", str(pairs[0][0]), str(pairs[1][0]), "--second-data", str(pairs[0][1]), str(pairs[1][1])]
    assert main([*base, *both_sets]) == 2  # both made with seed 0: the same parts
    assert "the same seed (0) holds the same parts" in capsys.readouterr().err.splitlines()[-1]
    for root in pairs[1]:  # the second pair: other parts (the fixture draws them alike)
        manifest = json.loads((root / "manifest.json").read_text())
        (root / "manifest.json").write_text(json.dumps({**manifest, "seed": 1}))
    one = tmp_path / "one.json"
    assert main([*base, "--data", str(pairs[0][0]), "--second-data", str(pairs[0][1]), "--out", str(one)]) == 0
    single = json.loads(one.read_text())
    both = tmp_path / "both.json"
    assert main([*base, *both_sets, "--out", str(both)]) == 0
    assert "42 parts of 2 twin sets judged by both cameras (18 good, 24 defective)" in capsys.readouterr().out
    pooled = json.loads(both.read_text())
    assert both.with_suffix(".png").read_bytes()[:4] == b"\x89PNG"  # the picture beside the JSON
    assert (pooled["parts"], pooled["good"], pooled["budget"]) == (42, 18, 4)  # floor(0.25 x 18), on 9: 2
    assert pooled["first"]["data"] == [str(pairs[0][0]), str(pairs[1][0])]
    scores = pooled["part_scores"]
    assert len(scores) == 42 and {s["set"] for s in scores} == {0, 1}
    assert sum(s["defective"] for s in scores) == 24
    assert {s["defect_type"] for s in scores if s["defective"]} == {"stain"}
    firsts = [s["first"] for s in single["part_scores"]]
    assert [s["first"] for s in scores if s["set"] == 0] == firsts  # set 0's parts score as they do alone
    assert [s["index"] for s in single["part_scores"]] == sorted({s["index"] for s in scores})
    assert main([*base, "--data", str(pairs[0][0]), str(pairs[0][0]), "--second-data", str(pairs[0][1]),
                 str(pairs[1][1])]) == 2
    assert "a set is named twice; its parts would count twice" in capsys.readouterr().err.splitlines()[-1]
    assert main([*base, "--data", str(pairs[0][0]), str(pairs[1][0]), "--second-data", str(pairs[0][1])]) == 2
    assert "--data names 2 sets and --second-data 1" in capsys.readouterr().err.splitlines()[-1]


def test_a_station_built_without_its_second_model_loads_it(tmp_path):
    """A caller that passes no second model (``station bench soak`` did): the station loads it from the config, so
    the second camera's frames are judged, not grabbed and ignored."""
    from station.assembly import build_station, load_detector
    from station.config import load_config
    from station.line_link import NoLink
    from tests.station.test_run import make_dataset, make_model, write_config

    model = make_model(tmp_path / "model" / "best")
    cfg = load_config(write_config(tmp_path, model, make_dataset(tmp_path / "ds"),
                                   f'[second_camera]\nenabled = true\nmodel = "{model}"\ndataset = "d"\n'))
    with InspectionLog(tmp_path / "log.sqlite") as log:
        station = build_station(cfg, load_detector(cfg), ScriptedCamera([]), NoLink(), log)
    assert isinstance(station.inspector, PairInspector) and station.second_threshold == 0.5


def write_eval(folder, labels, types, scores, threshold, unjudged=None, faces=None):
    """A ``station eval --out`` folder's two files that ``station compare`` reads (``faces``: its face column)."""
    folder.mkdir(parents=True)
    face = [""] * len(labels) if faces is None else [f",{f}" for f in faces]
    rows = "".join(f"{i},{y},{t},{s}{f}\n"
                   for i, (y, t, s, f) in enumerate(zip(labels, types, scores, face, strict=True)))
    (folder / "scores.csv").write_text("index,label,defect_type,score" + ("" if faces is None else ",face") + "\n"
                                       + rows)
    (folder / "eval.json").write_text(json.dumps({"threshold": threshold, "industrial": [{"defect_type": "all"}],
                                                  "unjudged": unjudged or {}}))
    return folder


def test_compare_split_scores_the_two_camera_station_on_held_out_parts(tmp_path, capsys):
    first = write_eval(tmp_path / "line", [0, 0, 0, 1, 1, 0], ["", "", "", "dent", "chip", ""],
                       [0.1, 0.2, 0.95, 0.99, 0.3, 0.1], 0.9)
    # the second camera sees part 5's scratch, which the first does not (label 0 there), and not part 0 at all
    second = write_eval(tmp_path / "side", [0, 0, 0, 1, 0, 1], ["", "", "", "dent", "", "scratch"],
                        [0.1, 0.6, 0.2, 0.4, 0.2, 0.9], 0.8, {"0": "no part in view"})
    split = tmp_path / "split.json"
    split.write_text(json.dumps({"splits": [{"first": 0.97, "second": 0.5, "k": 1, "good_rejected": 3, "caught": 0.8}],
                                 "chosen": 0}))
    assert main(["compare", str(first), str(second), "--split", str(split), "--out", str(tmp_path / "out")]) == 0
    rules = json.loads((tmp_path / "out" / "two-cameras.json").read_text())["rules"]
    assert [(r["good_rejected"], r["caught"]) for r in rules] == [(1, 1), (1, 1), (2, 2)]
    assert [r["defective"] for r in rules] == [3, 3, 3]  # a part is defective when either camera shows its defect
    assert rules[2]["by_type"] == {"chip": 0.0, "dent": 1.0, "scratch": 1.0}
    assert round(rules[2]["gain_points"], 1) == 33.3 and round(rules[2]["gain_se"], 1) == 33.3
    assert "frames not judged: first camera 0, second camera 1" in capsys.readouterr().out
    assert main(["compare", str(first), "--split", str(split), "--out", str(tmp_path / "o2")]) == 2
    assert "by the face" not in (tmp_path / "out" / "two-cameras.md").read_text()  # reports before faces: no table


def test_compare_split_says_what_each_face_loses_when_the_reports_know_the_faces(tmp_path):
    first = write_eval(tmp_path / "line", [0, 0, 1, 1, 0], ["", "", "dent", "chip", ""], [0.1, 0.2, 0.99, 0.3, 0.1],
                       0.9, faces=["", "", "top", "edge", ""])
    # the side report knows the face of the scratch only it sees; the line report's faces stand for the rest
    second = write_eval(tmp_path / "side", [0, 0, 1, 0, 1], ["", "", "dent", "", "scratch"], [0.1, 0.6, 0.4, 0.2, 0.9],
                        0.8, faces=["", "", "top", "", "front"])
    split = tmp_path / "split.json"
    split.write_text(json.dumps({"splits": [{"first": 0.97, "second": 0.5, "k": 1, "good_rejected": 1, "caught": 0.7}],
                                 "chosen": 0}))
    assert main(["compare", str(first), str(second), "--split", str(split), "--out", str(tmp_path / "out")]) == 0
    rules = json.loads((tmp_path / "out" / "two-cameras.json").read_text())["rules"]
    assert [r["by_face"] for r in rules] == [{"top": 1.0, "front": 0.0, "edge": 0.0},
                                             {"top": 0.0, "front": 1.0, "edge": 0.0},
                                             {"top": 1.0, "front": 1.0, "edge": 0.0}]
    md = (tmp_path / "out" / "two-cameras.md").read_text()
    assert "| rule | top (1) | front (1) | edge (1) |" in md and "0 of unknown face left out" in md


def test_station_split_prints_thresholds_that_keep_its_decisions():
    """The printed station.toml line rounded 0.9910132884979248 (a good part's score, which the split passes) down to
    0.991013: a station set from it rejected that part. The printed value is never below the split's threshold and
    below the next float32 score, so every score is decided as the split counted it."""
    import numpy as np

    from station.commands.split import config_number
    from station.decision import decide

    for x in (float(np.float32(v)) for v in (0.9910132884979248, 0.9863905906677246, 0.5, 0.98, 0.123456789, 1, 0)):
        text = config_number(x)
        assert x <= float(text) < float(np.nextafter(np.float32(x), np.float32(2))) or x == float(text) == 1.0
        assert len(text.replace(".", "").lstrip("0")) <= 9  # readable: 6-9 significant digits (float32 has 7-8)
        assert decide(float(np.float32(x)), float(text)).decision.value == "pass"
        above = float(np.nextafter(np.float32(x), np.float32(2)))
        assert x == 1.0 or decide(above, float(text)).decision.value == "reject"
    assert config_number(0.9910132884979248) == "0.9910133"
