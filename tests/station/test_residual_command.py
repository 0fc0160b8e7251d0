"""``station residual``: residual networks added to a detector with a variation model, trained on its set's train
split, calibrated and thresholded on the val split, recorded in the sidecar, reported by ``station eval``; errors in
one line."""

from __future__ import annotations

import contextlib
import json
from pathlib import Path

import pytest
import torch
from line_sets import make_line_set
from test_variation_command import trained  # same folder (pytest puts it on sys.path)

from station.cli import main


def test_residual_networks_are_trained_recorded_thresholded_and_evaluated(tmp_path: Path, capsys) -> None:
    data, model = trained(tmp_path, capsys)
    var = tmp_path / "v"
    assert main(["variation", "--model", str(model), "--data", str(data), "--out", str(var)]) == 0
    capsys.readouterr()
    out = tmp_path / "r"
    assert main(["residual", "--model", str(var), "--data", str(data), "--out", str(out), "--members", "2",
                 "--steps", "3", "--holdout-type", "stain"]) == 0
    cap = capsys.readouterr()
    assert "2 residual networks decide" in cap.out and "residual network 2/2: step 3/3" in cap.err
    meta = json.loads(out.with_suffix(".json").read_text())
    assert meta["model"]["decision"] == "residual" and meta["model"]["residual_members"] == 2
    assert 0.0 <= meta["threshold"] <= 1.0
    rec = meta["train"]["residual"]
    assert rec["holdout_type"] == "stain" and rec["defective_parts"] == 0 and rec["good_parts"] > 8
    assert rec["members"] == 2 and rec["steps"] == 3 and rec["from"] == str(var)
    assert main(["eval", "--model", str(out), "--data", str(data), "--no-plots", "--no-synthetic",
                 "--out", str(tmp_path / "ev")]) == 0
    report = json.loads((tmp_path / "ev" / "eval.json").read_text())
    assert all(0.0 <= r["residual"] <= 1.0 for r in report["detectors"])
    assert "held out" in capsys.readouterr().out  # the type left out of the networks' training is marked
    # twice: a model that has them already is refused in one line
    assert main(["residual", "--model", str(out), "--data", str(data), "--out", str(tmp_path / "r2"),
                 "--steps", "1"]) == 2
    err = capsys.readouterr().err
    assert "already has residual networks" in err and len(err.strip().splitlines()) == 1
    # and its variation model is not refitted under them: they read that fit
    assert main(["variation", "--model", str(out), "--data", str(data), "--refit",
                 "--out", str(tmp_path / "v2")]) == 2
    err = capsys.readouterr().err
    assert "residual networks" in err and len(err.strip().splitlines()) == 1


def test_a_model_without_the_variation_model_or_a_bad_type_is_refused_in_one_line(tmp_path: Path, capsys) -> None:
    data, model = trained(tmp_path, capsys)
    assert main(["residual", "--model", str(model), "--data", str(data), "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err
    assert "add it first (station variation)" in err and len(err.strip().splitlines()) == 1
    assert main(["residual", "--model", str(model), "--data", str(data), "--out", str(tmp_path / "r"),
                 "--holdout-type", "crack"]) == 2
    assert "not a defect type" in capsys.readouterr().err


def test_second_look_networks_keep_the_decision_and_need_the_second_look(tmp_path: Path, capsys) -> None:
    data, model = trained(tmp_path, capsys)
    var = tmp_path / "v"
    assert main(["variation", "--model", str(model), "--data", str(data), "--out", str(var)]) == 0
    capsys.readouterr()
    out = tmp_path / "r"
    assert main(["residual", "--model", str(var), "--data", str(data), "--out", str(out), "--members", "1",
                 "--steps", "3", "--second-look"]) == 0
    assert "1 residual networks are the variation model's second look" in capsys.readouterr().out
    meta = json.loads(out.with_suffix(".json").read_text())
    assert meta["model"]["decision"] == "variation" and meta["model"]["residual_members"] == 1
    assert meta["train"]["residual"]["look"] is True
    assert meta["train"]["variation"]["second_look_references"] > 0  # the model's own record is kept
    assert main(["eval", "--model", str(out), "--data", str(data), "--no-plots", "--no-synthetic",
                 "--out", str(tmp_path / "ev")]) == 0
    capsys.readouterr()
    few = tmp_path / "few"  # fitted on 12 good parts: no second look to join
    assert main(["variation", "--model", str(model), "--data", str(data), "--fit-parts", "12", "--out",
                 str(few)]) == 0
    capsys.readouterr()
    assert main(["residual", "--model", str(few), "--data", str(data), "--out", str(tmp_path / "r2"),
                 "--members", "1", "--steps", "1", "--second-look"]) == 2
    err = capsys.readouterr().err
    assert "second look" in err and len(err.strip().splitlines()) == 1


def test_more_defects_are_learned_from_and_recorded_and_a_set_without_them_refused(tmp_path: Path, capsys) -> None:
    data, model = trained(tmp_path, capsys)
    var = tmp_path / "v"
    assert main(["variation", "--model", str(model), "--data", str(data), "--out", str(var)]) == 0
    capsys.readouterr()
    more = make_line_set(tmp_path / "more", n=20, seed=7, defective=lambda i: i % 2 == 0, kind=lambda i: "chip")
    out = tmp_path / "r"
    assert main(["residual", "--model", str(var), "--data", str(data), "--out", str(out), "--members", "1",
                 "--steps", "2", "--more-defects", str(more)]) == 0
    assert "from --more-defects" in capsys.readouterr().err
    rec = json.loads(out.with_suffix(".json").read_text())["train"]["residual"]
    assert rec["more_defects"][0]["data"] == str(more) and rec["more_defects"][0]["manifest_sha256"]
    assert main(["residual", "--model", str(var), "--data", str(data), "--out", str(tmp_path / "r1"), "--members",
                 "1", "--steps", "2"]) == 0
    capsys.readouterr()
    alone = json.loads((tmp_path / "r1.json").read_text())["train"]["residual"]["defective_parts"]
    assert rec["defective_parts"] > alone > 0  # the other set's defective train parts were added to the set's own
    # the kinds learned from are recorded (station eval's in_training column reads them): the set's and the other's
    assert rec["types"] == ["chip", "stain"]
    assert json.loads((tmp_path / "r1.json").read_text())["train"]["residual"]["types"] == ["stain"]
    # a set whose train split has no defective parts (or only the held-out type's) is refused in one line, once
    # loaded (after the loading progress), before any training
    for extra in (["--holdout-type", "chip"], []):
        plain = make_line_set(tmp_path / "plain", n=10, seed=8) if not extra else more
        assert main(["residual", "--model", str(var), "--data", str(data), "--out", str(tmp_path / "r2"),
                     "--steps", "1", "--more-defects", str(plain), *extra]) == 2
        err = capsys.readouterr().err
        assert f"--more-defects {plain}: no defective" in err.splitlines()[-1] and "residual network" not in err
    assert main(["residual", "--model", str(var), "--data", str(data), "--out", str(tmp_path / "r2"), "--steps", "1",
                 "--more-defects", str(data)]) == 2  # the training set twice: refused before loading
    err = capsys.readouterr().err
    assert "the training set itself" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "r2.json").exists()


def test_a_held_out_type_stays_out_of_the_parts_that_threshold_the_model(tmp_path: Path, capsys) -> None:
    """Held out means held out: the val parts of the type left out of the residual networks' training set no
    threshold, neither `station residual`'s nor a later `station threshold`'s; the other types' do."""
    data, model = trained(tmp_path, capsys)
    var = tmp_path / "v"
    assert main(["variation", "--model", str(model), "--data", str(data), "--out", str(var)]) == 0
    val = make_line_set(tmp_path / "val", n=60, defective=lambda i: i % 3 == 1, validation=True, seed=1,
                        kind=lambda i: "chip" if i % 2 else "stain")
    n_chips = sum(1 for i in range(60) if i % 3 == 1 and i % 2)  # 10 chips, 10 stains
    for held, defective in (("stain", n_chips), (None, 20)):
        out = tmp_path / f"r-{held}"
        assert main(["residual", "--model", str(var), "--data", str(data), "--val-data", str(val), "--out", str(out),
                     "--members", "1", "--steps", "2", "--second-look",
                     *(["--holdout-type", held] if held else [])]) == 0
        rec = json.loads(out.with_suffix(".json").read_text())["train"]["residual"]
        assert rec["calibration_defective"] == defective and rec["calibration_parts"] == 40
        assert main(["threshold", "--model", str(out), "--data", str(val)]) == 0
        assert json.loads(out.with_suffix(".json").read_text())["train"]["threshold_set"]["n_defective"] == defective
    capsys.readouterr()


def test_an_interrupted_training_continues_where_it_stopped_and_its_states_go_once_saved(
        tmp_path: Path, capsys, monkeypatch: pytest.MonkeyPatch) -> None:
    import model.draem.residual as residual

    data, model = trained(tmp_path, capsys)
    var = tmp_path / "v"
    assert main(["variation", "--model", str(model), "--data", str(data), "--out", str(var)]) == 0
    out, states = tmp_path / "r", tmp_path / "r.resume"
    args = ["residual", "--model", str(var), "--data", str(data), "--out", str(out), "--members", "2", "--steps", "3"]
    real, steps_run = residual.training_loss, [0]

    def counted(kill_at: int | None):
        def loss(*a: torch.Tensor) -> torch.Tensor:
            steps_run[0] += 1
            if steps_run[0] == kill_at:
                raise KeyboardInterrupt  # the session ends in the second network's second step
            return real(*a)
        return loss

    monkeypatch.setattr(residual, "training_loss", counted(5))
    assert main(args) == 130
    assert (states / "member-0.pt").is_file() and not out.with_suffix(".json").exists()
    capsys.readouterr()
    # another training into the same --out: refused in one line naming the folder and what differs
    assert main([*args, "--seed", "4"]) == 2
    err = capsys.readouterr().err
    assert f"{states}: the resume states of another training (seed differ)" in err
    assert len(err.strip().splitlines()) == 1
    # the same training again, the set named by another path: the first network is not trained again, the second
    # from its start
    steps_run[0] = 0
    monkeypatch.setattr(residual, "training_loss", counted(None))
    assert main([a if a != str(data) else f"{data}/." for a in args]) == 0
    assert steps_run[0] == 3 and out.with_suffix(".json").is_file() and not states.exists()
    assert "2 residual networks decide" in capsys.readouterr().out


def test_lens_copies_are_placed_by_the_sets_frame_recorded_and_a_bad_range_refused_in_one_line(
        tmp_path: Path, capsys) -> None:
    """``--lens-copies LO,HI``: the lens copies' vignetting range, the set's frame (its manifest's height and width)
    and the model's view in it go into the sidecar's ``train.residual.lens_copies``; a range outside [0, 1) is one
    line naming the flag, before any training."""
    data, model = trained(tmp_path, capsys)
    var = tmp_path / "v"
    assert main(["variation", "--model", str(model), "--data", str(data), "--out", str(var)]) == 0
    out = tmp_path / "r"
    assert main(["residual", "--model", str(var), "--data", str(data), "--out", str(out), "--members", "1",
                 "--steps", "2", "--lens-copies", "0,0.3"]) == 0
    manifest = json.loads((Path(data) / "manifest.json").read_text())
    rec = json.loads(out.with_suffix(".json").read_text())["train"]["residual"]["lens_copies"]
    assert rec["vignetting"] == [0.0, 0.3] and rec["frame"] == [manifest["height"], manifest["width"]]
    top, left, h, w = rec["box"]
    assert 0 <= top and top + h <= manifest["height"] and 0 <= left and left + w <= manifest["width"]
    capsys.readouterr()
    for bad in ("0.2,1.5", "a"):
        with pytest.raises(SystemExit) if bad == "a" else contextlib.nullcontext():
            assert main(["residual", "--model", str(var), "--data", str(data), "--out", str(tmp_path / "r2"),
                         "--steps", "1", "--lens-copies", bad]) == 2
        err = capsys.readouterr().err
        assert "--lens-copies" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "r2.json").exists()
