"""``station pick``: of several files, the one rejecting fewest good val parts of a set as the station judges them
is copied to --out with every draw's counts in its sidecar; ties go to the first named; errors in one line."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from line_sets import make_line_set, make_model  # same folder (pytest puts it on sys.path)

from model.draem.checkpoint import load_checkpoint, save_checkpoint, sha256_file
from station.cli import main
from station.evaluation import load_and_evaluate


def test_the_draw_rejecting_fewest_good_parts_is_kept_and_recorded(tmp_path: Path, capsys) -> None:
    data = make_line_set(tmp_path / "val", n=24, defective=lambda i: i % 3 == 1, validation=True)
    base = make_model(tmp_path / "base")
    _, _, sp, _, ev = load_and_evaluate(str(base), data, "val")
    scores, good = np.asarray(ev.scores), sp.label.numpy() == 0
    det = load_checkpoint(base).detector
    files = {}
    for name, t in (("strict", float(scores.min()) / 2), ("loose", float(scores.max())),  # strict: every part
                    ("loose2", float(scores.max()))):
        files[name] = tmp_path / name
        save_checkpoint(files[name], det, threshold=t, threshold_rule="test")
    out = tmp_path / "kept"
    assert main(["pick", "--models", str(files["strict"]), str(files["loose"]), str(files["loose2"]),
                 "--data", str(data), "--out", str(out)]) == 0
    said = capsys.readouterr().out.strip().splitlines()
    n_good = int(good.sum())
    assert said[0].startswith(f"{files['strict']}: ") and f"of {n_good} good rejected" in said[0]
    assert said[1].startswith(f"{files['loose']}: 0 of {n_good} good rejected")
    assert said[-1].startswith(f"kept: {files['loose']} (")  # loose2 ties with it: the first named
    assert sha256_file(out.with_suffix(".pt")) == sha256_file(files["loose"].with_suffix(".pt"))
    rec = json.loads(out.with_suffix(".json").read_text())["train"]["draw_choice"]
    assert rec["kept"] == str(files["loose"]) and rec["data"] == str(data) and rec["split"] == "val"
    assert [d["name"] for d in rec["draws"]] == [str(p) for p in files.values()]
    assert rec["draws"][0]["good_rejected"] == n_good and rec["draws"][1]["good_rejected"] == 0
    assert load_checkpoint(out).threshold == load_checkpoint(files["loose"]).threshold


def test_a_bad_choice_is_refused_in_one_line(tmp_path: Path, capsys) -> None:
    data = make_line_set(tmp_path / "val", n=6, validation=True)
    a, b = make_model(tmp_path / "a"), make_model(tmp_path / "b")
    cases = [([str(a)], "at least two files"), ([str(a), str(a)], "named twice"),
             ([str(a), str(b)], "--out"), ([str(a), str(tmp_path / "none")], "none")]
    for models, words in cases:
        out = str(a) if words == "--out" else str(tmp_path / "out")
        assert main(["pick", "--models", *models, "--data", str(data), "--out", out]) == 2
        err = capsys.readouterr().err
        assert words in err and len(err.strip().splitlines()) == 1, err
    assert not (tmp_path / "out.json").exists()
