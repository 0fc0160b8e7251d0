"""station.toml loading: the shipped file equals the defaults, and every bad input is one clear line."""

from __future__ import annotations

import dataclasses
import subprocess
import sys
from pathlib import Path

import pytest

from station.config import ConfigError, StationConfig, load_config, parse_config

ROOT = Path(__file__).resolve().parents[2]


def test_shipped_station_toml_documents_exactly_the_defaults():
    cfg = load_config(ROOT / "station.toml")
    assert cfg == StationConfig()
    text = (ROOT / "station.toml").read_text()
    for table in dataclasses.fields(StationConfig):
        if table.name == "source":
            continue
        assert f"[{table.name}]" in text
        for key in dataclasses.fields(table.type if isinstance(table.type, type) else getattr(cfg, table.name)):
            assert f"{key.name} =" in text, f"station.toml does not document [{table.name}] {key.name}"


def test_values_are_typed():
    cfg = parse_config('[camera]\nexposure_us = 500\nkind = "aravis"\n[priors]\nbit_depth = 12\n'
                       "angles_deg = [[0, 45], [135, 90]]\n[acquisition]\nmax_frame_delay_ms = 60\n")
    assert cfg.acquisition.max_frame_delay_ms == 60.0 and StationConfig().acquisition.max_frame_delay_ms is None
    assert cfg.camera.exposure_us == 500.0 and isinstance(cfg.camera.exposure_us, float)
    assert cfg.camera.kind == "aravis" and cfg.priors.bit_depth == 12
    assert cfg.decision.threshold is None
    assert cfg.priors.mosaic_layout().angles_deg == ((0, 45), (135, 90))
    assert StationConfig().priors.mosaic_layout().name == "imx250mzr"


@pytest.mark.parametrize(("text", "message"), [
    ("[camera]\nexposure_us = -5", r"station.toml: \[camera\] exposure_us: -5.0 is out of range"),
    ("[camera]\nexposur_us = 1", r"\[camera\] exposur_us: unknown key"),
    ("[camra]\nx = 1", "camra: unknown key"),
    ('[camera]\nexposure_us = "fast"', r"exposure_us: expected a number, got 'fast'"),
    ("[camera]\nwidth = 641", "width: 641 must be even"),
    ('[camera]\ntrigger = "line9"', "trigger: 'line9' is not one of"),
    ("[camera]\nreconnect = 1", "reconnect: expected true or false"),
    ("[camera]\ntimeout_ms = 1.5", "timeout_ms: expected an integer"),
    ('[priors]\ndemosaic = "magic"', "demosaic: 'magic' is not one of 'bilinear'"),
    ("[priors]\nangles_deg = [[0, 45], [90, 90]]", "angles_deg: need"),
    ("[camera]\ndome_segments = [0]", r"\[camera\] dome_segments: \[0.0\]: two or more distinct azimuths"),
    ('[camera]\ndome_segments = [0, 180]\ntrigger = "free_run"\n[io]\nmode = "none"',
     "a frame per segment needs trigger = 'software'"),
    ('[camera]\ndome_segments = [0, 180]\ntrigger = "line0"\nexposure_us = 30000\n'
     '[acquisition]\nmax_frame_delay_ms = 50',
     "max_frame_delay_ms: 2 exposures of 30 ms take 60 ms"),
    ("[camera]\ndome_segments = [0, 180]\nexposure_us = 60000", "2 exposures of 60 ms take 120 ms, the whole"),
    ("[decision]\nthreshold = 2", r"threshold: 2.0 is out of range \[0, 1\]"),
    ("camera = 3", "camera: expected a table"),
    ("[camera\n", "not valid TOML.*line 1"),
    # a free-running camera's frames are not tied to the parts the PLC announces: each part was judged on a frame
    # taken before it arrived (an earlier part's)
    ('[camera]\ntrigger = "free_run"', r"\[camera\] trigger: 'free_run' with \[io\] mode 'sim_plc'"),
    ('[camera]\ntrigger = "free_run"\n[io]\nmode = "serial"\nport = "/dev/ttyS0"', r"trigger: 'free_run' with"),
    # a grab that gives up before the exposure is over takes that frame for the next part
    ("[camera]\nexposure_us = 50000\ntimeout_ms = 20", r"\[camera\] timeout_ms: 20 ms does not cover"),
])
def test_bad_config_names_the_key_and_reason(text, message):
    with pytest.raises(ConfigError, match=message):
        parse_config(text, "station.toml")


def test_a_frame_set_on_a_line_trigger_is_taken_when_its_exposures_fit_the_frame_delay():
    cfg = parse_config('[camera]\ndome_segments = [0, 180]\ntrigger = "line0"\nexposure_us = 10000\n'
                       "[acquisition]\nmax_frame_delay_ms = 40\n", "station.toml")
    assert cfg.camera.frames_per_part == 2 and cfg.camera.trigger == "line0"


def test_missing_file_is_named(tmp_path):
    with pytest.raises(ConfigError, match=r"nope\.toml: configuration file not found"):
        load_config(tmp_path / "nope.toml")


def test_cli_prints_one_line_not_a_traceback(tmp_path):
    bad = tmp_path / "station.toml"
    bad.write_text("[io]\nbaudrate = 12\n")
    r = subprocess.run([sys.executable, "-m", "station.cli", "config", "--config", str(bad)],
                       capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 2
    assert r.stderr.strip().splitlines() == [f"station config: error: {bad}: [io] baudrate: 12 is out of range "
                                             "[300, 4e+06]"]
    ok = subprocess.run([sys.executable, "-m", "station.cli", "config", "--config", str(ROOT / "station.toml")],
                        capture_output=True, text=True, cwd=ROOT)
    assert ok.returncode == 0 and "OK" in ok.stdout


def test_station_config_prints_valid_toml_that_loads_back_to_the_same_settings(tmp_path, capsys):
    import tomllib

    from station.cli import main
    from station.config import load_config, parse_config

    assert main(["config", "--config", "station.toml"]) == 0
    text = capsys.readouterr().out
    assert "True" not in text and "(not set)" in text  # unset keys are commented out, not invalid TOML
    tomllib.loads(text)
    again = parse_config(text, "printed")
    assert dataclasses.replace(again, source="x") == dataclasses.replace(load_config("station.toml"), source="x")


def test_every_option_with_a_default_shows_it_in_help_and_bench_help_is_whole_sentences():
    import argparse

    from station.cli import build_parser

    hidden = []

    def walk(parser: argparse.ArgumentParser, name: str) -> None:
        text = parser.format_help()
        formatter = parser._get_formatter()
        for a in parser._actions:
            if isinstance(a, argparse._SubParsersAction):
                for sub_name, sub in a.choices.items():
                    walk(sub, f"{name} {sub_name}")
            elif (a.option_strings and a.default is not None and a.default is not False
                  and a.default != argparse.SUPPRESS and a.help != argparse.SUPPRESS):
                if "default" not in formatter._get_help_string(a).lower():
                    hidden.append(f"{name} {a.option_strings[-1]}")
        assert "``" not in text, f"{name}: reStructuredText in help"

    walk(build_parser(), "station")
    assert not hidden, hidden
    bench = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction)).choices["bench"]
    helps = [c.help for a in bench._actions if isinstance(a, argparse._SubParsersAction) for c in a._choices_actions]
    assert helps and all(h.endswith((".", ")")) or "." not in h for h in helps), helps


def test_a_bad_argument_is_one_line_without_the_usage_block():
    r = subprocess.run([sys.executable, "-m", "station.cli", "render", "--out", "x", "--shard", "3/2"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert r.stderr.startswith("station render: error:") and "--shard" in r.stderr


def test_a_seed_out_of_range_is_one_line_in_every_command(capsys):
    """-1 and 2**80 gave tracebacks from numpy and torch (residual, adapt, serve-camera, train). In process (the
    parser refuses before any command runs); one run through the real entry point below."""
    from station.cli import main

    for command in ("residual", "adapt", "serve-camera", "train", "render", "normals", "import"):
        for bad in ("-1", str(2**80), "x"):
            with pytest.raises(SystemExit) as exc:
                main([command, "--seed", bad])
            err = capsys.readouterr().err
            assert exc.value.code == 2 and "Traceback" not in err, (command, bad, err)
            assert "--seed" in err and len(err.strip().splitlines()) == 1, (command, bad, err)
    r = subprocess.run([sys.executable, "-m", "station.cli", "train", "--seed", str(2**80)], capture_output=True,
                       text=True)
    assert r.returncode == 2 and "--seed" in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr


def test_a_time_that_is_not_a_number_is_refused():
    """--since nan exported 0 rows and said nothing."""
    r = subprocess.run([sys.executable, "-m", "station.cli", "export-log", "--since", "nan", "--out", "x.csv"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "--since" in r.stderr and "not a time" in r.stderr


def test_view_and_compare_refuse_what_they_cannot_use(tmp_path):
    """`station view --seconds nan` never closed, `--layout bogus` was accepted; `station compare` on a binary
    eval.json printed a UnicodeDecodeError traceback."""
    (tmp_path / "ev").mkdir()
    (tmp_path / "ev" / "eval.json").write_bytes(b"\xff\xfe\x00")
    for argv, needle in ((["view", "--seconds", "nan"], "--seconds"), (["view", "--layout", "bogus"], "--layout"),
                         (["compare", str(tmp_path / "ev"), "--out", str(tmp_path / "c")], "eval.json")):
        r = subprocess.run([sys.executable, "-m", "station.cli", *argv], capture_output=True, text=True)
        assert r.returncode == 2 and "Traceback" not in r.stderr and needle in r.stderr, (argv, r.stderr)


def test_benchmark_sizes_and_counts_that_cannot_run_are_one_line():
    """bench priors --width 63, model --repeats 0, pipeline --parts 0, defects --size 0, render --scenes 0 gave
    tracebacks; soak --parts 0 exited 0 and --sample-s 0 spun."""
    for argv in (["priors", "--width", "63"], ["model", "--repeats", "0"], ["pipeline", "--parts", "0"],
                 ["defects", "--size", "0"], ["render", "--scenes", "0"], ["soak", "--parts", "0"],
                 ["soak", "--sample-s", "0"]):
        r = subprocess.run([sys.executable, "-m", "station.cli", "bench", *argv], capture_output=True, text=True)
        assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and argv[1] in r.stderr, (argv, r.stderr)


def test_counts_and_budgets_of_the_model_commands_are_checked():
    """train --max-minutes nan was ignored, --size 0 became the preset's; normals --limit 0 meant all samples and
    --threads 0 was ignored; eval/adapt --limit 0 said "no usable samples" instead of naming the flag."""
    for argv in (["train", "--max-minutes", "nan"], ["train", "--size", "0"], ["normals", "--limit", "0"],
                 ["normals", "--threads", "0"], ["eval", "--limit", "-3"], ["adapt", "--limit", "0"]):
        r = subprocess.run([sys.executable, "-m", "station.cli", *argv], capture_output=True, text=True)
        assert r.returncode == 2 and argv[1] in r.stderr and len(r.stderr.strip().splitlines()) == 1, (argv, r.stderr)


def test_the_last_bad_inputs_of_the_cli_audit_are_one_line(tmp_path):
    """normals --model "" started a training; a scene config value of the wrong type raised TypeError; an
    inspection log path that is a folder said "disk I/O error"."""
    scene = tmp_path / "scene.toml"
    scene.write_text('[scene]\ncamera_radius_m = "abc"\n')
    (tmp_path / "folder").mkdir()
    for argv, needle in ((["normals", "--model", ""], "--model"),
                         (["render", "--out", str(tmp_path / "s"), "--count", "1", "--config", str(scene)],
                          "camera_radius_m"),
                         (["report", "--db", str(tmp_path / "folder"), "--out", str(tmp_path / "r")], "folder")):
        r = subprocess.run([sys.executable, "-m", "station.cli", *argv], capture_output=True, text=True, timeout=60)
        assert r.returncode == 2 and "Traceback" not in r.stderr and needle in r.stderr, (argv, r.stderr)
        assert len(r.stderr.strip().splitlines()) == 1, (argv, r.stderr)
