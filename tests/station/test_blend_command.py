"""``station blend``: a model's look network blended with its window on every part, on a small rendered line set:
the two thresholds and the weight recorded, the threshold set on the val split, the scores the rule's, ``station
eval`` reading the file; errors in one line."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from test_variation_command import trained  # same folder (pytest puts it on sys.path)

from model.draem.checkpoint import load_checkpoint
from station.cli import main


def test_the_blend_is_calibrated_recorded_thresholded_and_evaluated(tmp_path: Path, capsys) -> None:
    data, model = trained(tmp_path, capsys)
    var, look, out = tmp_path / "v", tmp_path / "look", tmp_path / "b"
    assert main(["variation", "--model", str(model), "--data", str(data), "--out", str(var)]) == 0
    capsys.readouterr()
    assert main(["blend", "--model", str(var), "--data", str(data), "--out", str(out)]) == 2  # no look to blend
    err = capsys.readouterr().err
    assert "station residual --second-look" in err and len(err.strip().splitlines()) == 1
    assert main(["residual", "--model", str(var), "--data", str(data), "--out", str(look), "--members", "1",
                 "--steps", "3", "--second-look"]) == 0
    capsys.readouterr()
    assert main(["blend", "--model", str(look), "--data", str(data), "--out", str(out), "--weight", "1.5"]) == 2
    err = capsys.readouterr().err
    assert "weight" in err and "(0, 1]" in err and len(err.strip().splitlines()) == 1
    assert main(["blend", "--model", str(look), "--data", str(data), "--out", str(out)]) == 0
    said = capsys.readouterr().out
    assert "the look blended (0.25 of the window's finding" in said and "asked about every part" in said
    meta = json.loads(out.with_suffix(".json").read_text())
    rec = meta["train"]["blend"]
    det = load_checkpoint(out).detector
    assert det.residual is not None and det.residual.blends
    assert det.residual.blend.tolist() == pytest.approx([0.25, rec["window_threshold"], rec["finding_threshold"]])
    assert rec["from"] == str(look) and rec["calibration_data"] == str(data) and rec["good_parts"] > 2
    assert 0.0 <= meta["threshold"] <= 1.0 and meta["threshold"] != json.loads(look.with_suffix(".json").read_text()
                                                                               )["threshold"]
    assert not load_checkpoint(look).detector.residual.blends  # the file it came from is left as it was
    assert main(["eval", "--model", str(out), "--data", str(data), "--no-plots", "--no-synthetic",
                 "--out", str(tmp_path / "ev")]) == 0
    report = json.loads((tmp_path / "ev" / "eval.json").read_text())
    assert all(0.0 <= r["combined"] <= 1.0 for r in report["detectors"])
