"""``station eval --split val --val-data OTHER``: a validation set of other kinds (or another seed) is scored against
the thresholds of the set the model was selected on, as a held-out set is. Its own val split as thresholds would be
in-sample, so ``--split val`` without another ``--val-data`` still gives no industrial figures."""

from __future__ import annotations

import json
from pathlib import Path

from line_sets import make_line_set
from test_run import make_model  # same folder (pytest puts it on sys.path)

from station.cli import main


def _eval(tmp_path: Path, name: str, *args: str) -> dict:
    out = tmp_path / name
    assert main(["eval", "--no-plots", "--no-synthetic", "--out", str(out), *args]) == 0
    return json.loads((out / "eval.json").read_text())


def test_a_val_split_is_scored_against_another_sets_thresholds(tmp_path: Path) -> None:
    line = make_line_set(tmp_path / "line", 40, defective=lambda i: i % 10 == 1)
    other = make_line_set(tmp_path / "other", 20, defective=lambda i: i % 2 == 0, validation=True, seed=1)
    model = str(make_model(tmp_path / "m" / "last", ("intensity", "aolp")))
    report = _eval(tmp_path, "other", "--model", model, "--data", str(other), "--split", "val",
                   "--val-data", str(line))
    assert report["industrial"], report["industrial_note"]
    assert f"val split of {line}" in report["industrial_note"]
    same = _eval(tmp_path, "same", "--model", model, "--data", str(other), "--split", "val",
                 "--val-data", str(other))
    assert not same["industrial"]
    assert not _eval(tmp_path, "own", "--model", model, "--data", str(other), "--split", "val")["industrial"]
