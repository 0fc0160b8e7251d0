"""``station train --rendered-fraction`` (mixed supervision from the set's rendered defective training parts) and
``--holdout-type`` (a defect type left out of them)."""

from __future__ import annotations

import json
from pathlib import Path

from line_sets import make_line_set  # same folder (pytest puts it on sys.path)

from station.cli import main

BASE = ["--priors", "intensity,aolp", "--preset", "tiny", "--fusion", "fused", "--size", "32", "--steps", "2",
        "--batch-size", "4", "--eval-every", "2", "--device", "cpu"]


def test_rendered_defects_of_the_train_split_join_every_batch_and_are_recorded(tmp_path: Path) -> None:
    data = make_line_set(tmp_path / "ds", n=30, defective=lambda i: i % 3 == 1)
    out = tmp_path / "train"
    assert main(["train", "--data", str(data), *BASE, "--rendered-fraction", "0.25", "--out", str(out)]) == 0
    side = json.loads((out / "best.json").read_text())
    meta = side["train"]
    manifest = json.loads((data / "manifest.json").read_text())
    assert side["model"]["frame_aspect"] == manifest["width"] / manifest["height"]  # the region's view (roi.py)
    assert meta["rendered_defects"]["fraction"] == 0.25 and meta["rendered_defects"]["parts"] > 0
    assert meta["rendered_defects"]["holdout_type"] is None and meta["rendered_defects"]["types"] == ["stain"]
    assert meta["train_config"]["rendered_fraction"] == 0.25


def test_holdout_and_fraction_errors_are_one_line(tmp_path: Path, capsys) -> None:
    data = make_line_set(tmp_path / "ds", n=30, defective=lambda i: i % 3 == 1)
    argv = ["train", "--data", str(data), *BASE, "--out", str(tmp_path / "t")]
    assert main([*argv, "--holdout-type", "stain"]) == 2
    assert "needs --rendered-fraction" in capsys.readouterr().err
    assert main([*argv, "--rendered-fraction", "0.25", "--holdout-type", "stain"]) == 2
    assert "besides stain" in capsys.readouterr().err  # the set's only type: nothing left to train on
    assert main([*argv, "--rendered-fraction", "0.25", "--holdout-type", "dent"]) == 2
    assert "no sample of type ['dent']" in capsys.readouterr().err
    assert main([*argv, "--rendered-fraction", "1.0"]) == 2
    assert "--rendered-fraction 1.0" in capsys.readouterr().err
    for flag, value in (("--eval-every", "0"), ("--batch-size", "0"), ("--polarization-noise", "2")):
        assert main([*argv, flag, value]) == 2
        err = capsys.readouterr().err
        assert f"{flag} {value}" in err and "--rendered-fraction" not in err  # the flag given, not another
    clean = make_line_set(tmp_path / "clean", n=30, defective=lambda i: False)
    assert main(["train", "--data", str(clean), *BASE, "--rendered-fraction", "0.25",
                 "--out", str(tmp_path / "c")]) == 2
    assert "no rendered defective parts in its train split" in capsys.readouterr().err


def test_eval_reports_parts_caught_at_fixed_false_rejects_per_type_with_training_status(tmp_path: Path,
                                                                                     capsys) -> None:
    data = make_line_set(tmp_path / "ds", n=40, defective=lambda i: i % 3 == 1)
    for name, extra in (("mixed", ["--rendered-fraction", "0.25"]), ("plain", [])):
        assert main(["train", "--data", str(data), *BASE, *extra, "--out", str(tmp_path / name)]) == 0
        assert main(["eval", "--model", str(tmp_path / name / "best"), "--data", str(data), "--no-plots",
                     "--no-synthetic", "--out", str(tmp_path / f"ev-{name}")]) == 0
        rep = json.loads((tmp_path / f"ev-{name}" / "eval.json").read_text())
        rows = {r["type"]: r for r in rep["industrial"]}
        assert set(rows) == {"all", "stain"} and 0.0 <= rows["all"]["caught_at_1%_false_rejects"] <= 1.0
        assert rows["stain"]["in_training"] == ("trained on" if name == "mixed" else "synthetic only")
        assert "held fixed" in rep["industrial_note"]
    assert "caught_at_5%_false_rejects" in capsys.readouterr().out


def test_a_held_out_type_is_left_out_of_validation_too(tmp_path: Path) -> None:
    """Keep-best and the threshold read the val split: a held-out type there would select the model on it."""
    data = make_line_set(tmp_path / "ds", n=60, defective=lambda i: i % 3 == 1,
                         kind=lambda i: "dent" if (i // 10) % 2 else "stain")
    val_types = ["dent" if (i // 10) % 2 else "stain" for i in range(60) if i % 10 == 2 and i % 3 == 1]
    assert "dent" in val_types and "stain" in val_types
    for name, extra in (("all", []), ("no-dent", ["--holdout-type", "dent"])):
        out = tmp_path / name
        assert main(["train", "--data", str(data), *BASE, "--rendered-fraction", "0.25", *extra,
                     "--out", str(out)]) == 0
        summary = json.loads((out / "train_summary.json").read_text())
        kept = [t for t in val_types if not extra or t != "dent"]
        assert summary["val_defective"] == len(kept)
        assert summary["val_parts"] == 6 - (len(val_types) - len(kept))


def test_init_fine_tunes_a_model_and_keeps_a_held_out_type_out_of_its_history(tmp_path: Path, capsys) -> None:
    data = make_line_set(tmp_path / "ds", n=60, defective=lambda i: i % 3 == 1,
                         kind=lambda i: "dent" if (i // 10) % 2 else "stain")
    plain = tmp_path / "plain"
    assert main(["train", "--data", str(data), *BASE, "--out", str(plain)]) == 0
    tuned = tmp_path / "tuned"
    argv = ["train", "--data", str(data), *BASE, "--rendered-fraction", "0.25"]
    assert main([*argv, "--holdout-type", "dent", "--init", str(plain / "last"), "--out", str(tuned)]) == 0
    meta = json.loads((tuned / "best.json").read_text())["train"]
    start = json.loads((plain / "last.json").read_text())
    assert meta["init"]["weights_sha256"] == start["weights_sha256"] and meta["init"]["step"] == 2
    assert json.loads((tuned / "last.json").read_text())["weights_sha256"] != start["weights_sha256"]
    # a model that trained on rendered dents cannot seed a run that holds dents out
    assert main([*argv, "--init", str(tmp_path / "tuned" / "last"), "--holdout-type", "stain",
                 "--out", str(tmp_path / "x")]) == 2
    assert "so stain would not be held out" in capsys.readouterr().err
    assert main([*argv, "--init", str(tmp_path / "nothing"), "--out", str(tmp_path / "y")]) == 2
    assert "--init" in capsys.readouterr().err
    other = ["train", "--data", str(data), BASE[0], "intensity", *BASE[2:], "--init", str(plain / "last"),
             "--out", str(tmp_path / "z")]
    assert main(other) == 2
    assert "init from a different model" in capsys.readouterr().err
    # the networks are convolutional: a centre-square model starts one that sees the band, at another size
    band = tmp_path / "band"
    assert main([*argv, "--roi", "band", "--size", "64", "--init", str(plain / "last"), "--out", str(band)]) == 0
    meta = json.loads((band / "last.json").read_text())
    assert meta["model"]["roi"] == "band" and meta["model"]["input_size_px"] == 64
    assert meta["train"]["init"]["weights_sha256"] == start["weights_sha256"]
    assert main(["eval", "--model", str(band / "last"), "--data", str(data), "--no-plots", "--no-synthetic",
                 "--out", str(tmp_path / "ev-band")]) == 0


def test_the_held_out_report_compares_trained_on_held_out_and_synthetic_only(tmp_path: Path, capsys) -> None:
    """A held-out set (every part test, its own seed) has no val split: --val-data fixes the thresholds from the
    training set's; station compare lines the reports up per type; the shipped copy keeps weights and int8."""
    from model.draem.checkpoint import copy_checkpoint, load_checkpoint

    kind = {"kind": lambda i: "dent" if (i // 10) % 2 else "stain", "defective": lambda i: i % 3 == 1}
    data = make_line_set(tmp_path / "ds", n=60, **kind)
    heldout = make_line_set(tmp_path / "ho", n=30, seed=5, heldout=True, **kind)
    runs = {"plain": [], "mixed": ["--rendered-fraction", "0.25"],
            "no-dent": ["--rendered-fraction", "0.25", "--holdout-type", "dent"]}
    for name, extra in runs.items():
        assert main(["train", "--data", str(data), *BASE, *extra, "--out", str(tmp_path / name)]) == 0
        argv = ["eval", "--model", str(tmp_path / name / "best"), "--data", str(heldout), "--no-plots",
                "--no-synthetic", "--out", str(tmp_path / f"ev-{name}")]
        assert main(argv) == 0  # without --val-data: evaluated, but no industrial rows (no val split)
        assert "has no val split (a held-out set)" in json.loads(
            (tmp_path / f"ev-{name}" / "eval.json").read_text())["industrial_note"]
        assert main([*argv, "--val-data", str(data)]) == 0
    capsys.readouterr()
    assert main(["compare", *(str(tmp_path / f"ev-{n}") for n in runs), "--out", str(tmp_path / "cmp")]) == 0
    rows = json.loads((tmp_path / "cmp" / "compare.json").read_text())["rows"]
    status = {(r["type"], r["in_training"]): r["model"].rsplit("-", 1)[-1] for r in rows}
    assert status == {("dent", "synthetic only"): "plain", ("dent", "held out"): "dent",
                      ("dent", "trained on"): "mixed", ("stain", "synthetic only"): "plain",
                      ("stain", "trained on"): "mixed"}
    assert (tmp_path / "cmp" / "compare.png").is_file() and "held out" in capsys.readouterr().out
    assert main(["compare", str(tmp_path / "nothing"), "--out", str(tmp_path / "c2")]) == 2
    assert "not a station eval report" in capsys.readouterr().err
    (tmp_path / "mixed" / "best.int8").mkdir()
    (tmp_path / "mixed" / "best.int8" / "int8.json").write_text("{}")
    copy_checkpoint(tmp_path / "mixed" / "best", tmp_path / "ship" / "default")
    shipped = load_checkpoint(tmp_path / "ship" / "default")
    assert shipped.meta["weights_file"] == "default.pt" and (tmp_path / "ship" / "default.int8" / "int8.json").is_file()
    assert shipped.meta["weights_sha256"] == load_checkpoint(tmp_path / "mixed" / "best").meta["weights_sha256"]


def test_a_schedule_stopped_at_a_step_and_resumed_equals_the_straight_run(tmp_path: Path, capsys) -> None:
    data = make_line_set(tmp_path / "ds", n=30)
    argv = ["train", "--data", str(data), *BASE[:8], "--steps", "4", "--batch-size", "2", "--eval-every", "2",
            "--device", "cpu"]
    assert main([*argv, "--out", str(tmp_path / "straight")]) == 0
    assert main([*argv, "--stop-at-step", "2", "--out", str(tmp_path / "split")]) == 0
    assert json.loads((tmp_path / "split" / "last.json").read_text())["train"]["step"] == 2
    assert main([*argv, "--out", str(tmp_path / "split")]) == 0
    done = [json.loads((tmp_path / d / "last.json").read_text()) for d in ("straight", "split")]
    assert [d["train"]["step"] for d in done] == [4, 4]
    assert done[0]["weights_sha256"] == done[1]["weights_sha256"]
    assert main([*argv, "--stop-at-step", "5", "--out", str(tmp_path / "bad")]) == 2
    assert "--stop-at-step 5" in capsys.readouterr().err


def test_a_validation_set_gives_keep_best_its_val_split_and_a_set_without_one_says_so(tmp_path: Path,
                                                                                     capsys) -> None:
    """``--val-data``: keep-best and the threshold read another set's val split (a validation set), for a training
    set that has none; without it, such a set is refused in one line that says how."""
    import shutil

    from sim.dataset import split_of
    from station.datasets import manifest_sha256

    data = make_line_set(tmp_path / "ds", n=30, defective=lambda i: i % 3 == 1)
    for i in range(30):  # the training set as the side camera's was rendered: no val split
        if split_of(i) == "val":
            shutil.rmtree(data / "samples" / f"{i:06d}")
    val = make_line_set(tmp_path / "val", n=12, seed=3, defective=lambda i: i % 3 == 1, validation=True)
    argv = ["train", "--data", str(data), *BASE, "--out", str(tmp_path / "t")]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "no complete samples in split 'val'" in err and "--val-data" in err and len(err.strip().splitlines()) == 1
    assert main([*argv, "--val-data", str(tmp_path / "nowhere")]) == 2
    err = capsys.readouterr().err
    assert "--val-data" in err and "nowhere" in err and len(err.strip().splitlines()) == 1
    assert main([*argv, "--val-data", str(val)]) == 0
    summary = json.loads((tmp_path / "t" / "train_summary.json").read_text())
    assert summary["val_parts"] == 12 and summary["val_defective"] == 4 and summary["val_kind"] == "rendered"
    rec = json.loads((tmp_path / "t" / "best.json").read_text())["train"]["val_data"]
    assert rec == {"data": str(val), "manifest_sha256": manifest_sha256(val)}  # which parts selected it


def test_a_val_split_without_a_good_part_is_refused_in_one_line(tmp_path: Path, capsys) -> None:
    """Keep-best falls back to synthetic anomalies on the val split's good parts when it lacks rendered defects or
    good parts; a val split of defective parts only has none to put them on (a small set drawn with --defects: make
    model's smoke run of 40 parts crashed in torch here). It is refused in one line naming the set."""
    from sim.dataset import split_of

    data = make_line_set(tmp_path / "ds", n=30, defective=lambda i: split_of(i) == "val" or i % 3 == 1)
    assert main(["train", "--data", str(data), *BASE, "--out", str(tmp_path / "t")]) == 2
    said = [line for line in capsys.readouterr().err.splitlines() if "no good part" in line]  # after the loading bars
    assert len(said) == 1 and str(data) in said[0] and "--val-data" in said[0]
