"""``station shape``: the shape check added to a model with a variation model, on a small rendered line set: the
part's bottom edge found, the check recorded in the sidecar, the threshold kept; errors in one line."""

from __future__ import annotations

import json
from pathlib import Path

from line_sets import make_line_set
from test_variation_command import trained  # same folder (pytest puts it on sys.path)

from model.draem.checkpoint import load_checkpoint
from station.cli import main


def test_the_shape_check_is_added_recorded_and_the_threshold_kept(tmp_path: Path, capsys) -> None:
    data, model = trained(tmp_path, capsys)
    var = tmp_path / "v"
    assert main(["variation", "--model", str(model), "--data", str(data), "--out", str(var)]) == 0
    capsys.readouterr()
    out = tmp_path / "s"
    # the set's own val split has 4 good parts: too few to set the check's threshold, said in one line
    assert main(["shape", "--model", str(var), "--data", str(data), "--val-data", str(data), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    errors = [line for line in err.splitlines() if "error:" in line]  # after the loading's progress
    assert len(errors) == 1 and "seen on 4 good validation parts; it needs 10" in errors[0]
    val = make_line_set(tmp_path / "val", n=16, seed=1, validation=True, defective=lambda i: False)
    assert main(["shape", "--model", str(var), "--data", str(data), "--val-data", str(val), "--out", str(out)]) == 0
    said = capsys.readouterr().out
    assert "shape check on the bottom edge over input columns" in said
    # too few of these small parts show the outline check's edges: it is off, and the line says why
    assert "no outline check (outline check: the edges are seen on" in said
    meta, before = json.loads(out.with_suffix(".json").read_text()), json.loads(var.with_suffix(".json").read_text())
    rec = meta["train"]["shape"]
    assert meta["threshold"] == before["threshold"] and rec["from"] == str(var) and rec["good_parts"] > 8
    assert rec["sag_spread_px"] > 0 and rec["threshold_z"] >= 1.0 and rec["window_at_threshold"] > 0
    assert "outline" in rec and rec["outline"] is None  # make-model's resumption looks for the key
    shape = load_checkpoint(out).detector.variation.shape
    assert shape.fitted and int(shape.edge[1]) - int(shape.edge[0]) >= 10
    assert not load_checkpoint(var).detector.variation.shape.fitted


def test_a_model_without_the_variation_model_is_refused_in_one_line(tmp_path: Path, capsys) -> None:
    data, model = trained(tmp_path, capsys)
    assert main(["shape", "--model", str(model), "--data", str(data), "--val-data", str(data),
                 "--out", str(tmp_path / "s")]) == 2
    err = capsys.readouterr().err
    assert "add it first (station variation)" in err and len(err.strip().splitlines()) == 1
