"""``station variation``: a trained detector plus the registered variation model, fitted on the set's good train
parts, calibrated and thresholded on its val split, recorded in the sidecar; errors in one line."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest
from line_sets import make_line_set  # same folder (pytest puts it on sys.path)

from station.cli import main

BASE = ["--preset", "tiny", "--fusion", "fused", "--size", "32", "--steps", "2", "--batch-size", "4",
        "--eval-every", "2", "--device", "cpu", "--roi", "band"]


def trained(tmp_path: Path, capsys, priors: str = "intensity,dolp,aolp") -> tuple[Path, Path]:
    """A 60-part line set (every third part defective) and a detector trained on it for 2 steps: (set, model)."""
    data = make_line_set(tmp_path / "ds", n=60, defective=lambda i: i % 3 == 1)
    assert main(["train", "--data", str(data), "--priors", priors, *BASE, "--out", str(tmp_path / "t")]) == 0
    capsys.readouterr()
    return data, tmp_path / "t" / "last"


def refused_naming(capsys, flag: str, value: str, model: Path, data: Path, out: Path) -> None:
    """``station variation`` with ``flag value`` exits 2 with one line that names the flag."""
    assert main(["variation", "--model", str(model), "--data", str(data), flag, value, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert flag in err and len(err.strip().splitlines()) == 1


def test_variation_is_fitted_recorded_thresholded_and_evaluated(tmp_path: Path, capsys) -> None:
    data, model = trained(tmp_path, capsys)
    out = tmp_path / "v"
    assert main(["variation", "--model", str(model), "--data", str(data), "--out", str(out)]) == 0
    line = capsys.readouterr().out
    assert "variation model fitted on" in line and "of good parts" in line
    meta = json.loads(out.with_suffix(".json").read_text())
    assert meta["model"]["variation"] is True and 0.0 <= meta["threshold"] <= 1.0
    assert meta["model"]["decision"] == "variation"  # the default is the shipped recipe
    rec = meta["train"]["variation"]
    assert rec["fit_parts"] > 8 and rec["calibration_parts"] >= 2 and rec["from"].endswith("last")
    # the shipped recipe keeps every good part fitted for a second look, whose gate (no test since rule 60) chooses
    # the parts a look network is asked about, and judges each place by its residual's curvature
    assert rec["second_look_references"] == rec["fit_parts"] and "a second look's gate only" in line
    assert rec["second_look_test"] is False and rec["curvature_sigma"] == 3.0
    assert main(["eval", "--model", str(out), "--data", str(data), "--no-plots", "--no-synthetic",
                 "--out", str(tmp_path / "ev")]) == 0
    report = json.loads((tmp_path / "ev" / "eval.json").read_text())
    assert [r["type"] for r in report["detectors"]] == ["all", "stain"] and not report["early_exit"]
    assert all(0.0 <= r[k] <= 1.0 for r in report["detectors"] for k in ("networks", "variation", "combined"))
    printed = capsys.readouterr().out
    assert "Image AUROC by detector" in printed and "Told where to look" in printed
    # the localised oracle: per type, what the features separate at 1 % of good parts and what the model caught
    told = report["told_where"]
    assert [r["type"] for r in told] == ["all", "stain"]
    assert told[0]["defects"] == report["rows"][0]["anomalous"]
    assert all(0.0 <= r[k] <= 1.0 for r in told for k in ("separable", "separable_pixels", "separable_mean", "caught"))
    assert told[0]["separable"] >= max(told[0]["separable_pixels"], told[0]["separable_mean"])
    # scores.csv says which defects the oracle separates, part by part
    with open(tmp_path / "ev" / "scores.csv", newline="") as fh:
        parts = list(csv.DictReader(fh))
    flags = [int(r["separable"]) for r in parts if r["label"] == "1"]
    assert all(r["separable"] == "" for r in parts if r["label"] == "0")
    assert len(flags) == told[0]["defects"] and sum(flags) == round(told[0]["separable"] * len(flags))
    # twice: a detector that already has one is refused in one line
    assert main(["variation", "--model", str(out), "--data", str(data), "--out", str(tmp_path / "w")]) == 2
    assert "already has a variation model" in capsys.readouterr().err


def test_a_validation_set_calibrates_and_thresholds_and_a_decision_is_recorded(tmp_path: Path, capsys) -> None:
    data = make_line_set(tmp_path / "ds", n=40, defective=lambda i: i % 10 == 1)  # 4 good val parts
    val = make_line_set(tmp_path / "val", n=30, seed=3, defective=lambda i: i % 3 == 1, validation=True)
    assert main(["train", "--data", str(data), "--priors", "intensity,dolp,aolp", *BASE,
                 "--out", str(tmp_path / "t")]) == 0
    capsys.readouterr()
    out = tmp_path / "v"
    assert main(["variation", "--model", str(tmp_path / "t" / "last"), "--data", str(data), "--val-data", str(val),
                 "--decision", "variation", "--out", str(out)]) == 0
    line = capsys.readouterr().out
    assert "on 30 val parts" in line and "decision: variation alone" in line
    meta = json.loads(out.with_suffix(".json").read_text())
    assert meta["model"]["decision"] == "variation"
    rec = meta["train"]["variation"]
    assert rec["calibration_data"] == str(val) and rec["calibration_parts"] == 20 and rec["data"] == str(data)
    assert rec["calibration_manifest_sha256"] != rec["manifest_sha256"]  # the validation set's own, recorded
    # and the industrial thresholds of an evaluation come from its 20 good parts, not the training set's 4
    assert main(["eval", "--model", str(out), "--data", str(data), "--val-data", str(val), "--no-plots",
                 "--no-synthetic", "--out", str(tmp_path / "ev")]) == 0
    assert f"val split of {val}, 20 good parts" in capsys.readouterr().out


def test_a_model_without_intensity_is_refused_in_one_line(tmp_path: Path, capsys) -> None:
    data, model = trained(tmp_path, capsys, priors="dolp,aolp")
    assert main(["variation", "--model", str(model), "--data", str(data),
                 "--out", str(tmp_path / "v")]) == 2
    err = capsys.readouterr().err
    assert "intensity" in err and len(err.strip().splitlines()) == 1


def test_fit_parts_fits_on_the_first_good_parts_only_and_is_recorded(tmp_path: Path, capsys) -> None:
    """``--fit-parts N``: how many good parts a line needs (a learning curve, docs/results) is asked with one flag."""
    data, model = trained(tmp_path, capsys)
    out = tmp_path / "v"
    assert main(["variation", "--model", str(model), "--data", str(data), "--fit-parts", "12",
                 "--out", str(out)]) == 0
    said = capsys.readouterr().out
    assert "fitted on 12 good parts" in said and "no second look (it needs >= 20 good parts)" in said
    train = json.loads(out.with_suffix(".json").read_text())["train"]
    assert train["variation"]["fit_parts"] == 12 and train["variation"]["second_look_references"] == 0
    # the drift monitor's trained range is the frames the deciding model was fitted on, not the networks' set (a
    # refit on another line's renders must not warn on every frame of that line)
    assert train["frame_statistics"]["n_frames"] == 12
    for bad in ("7", "0"):  # fewer than the fit needs: one line naming the flag, before any loading
        refused_naming(capsys, "--fit-parts", bad, model, data, tmp_path / "w")


def test_blur_copies_fit_the_model_on_blurred_copies_too_and_are_recorded(tmp_path: Path, capsys) -> None:
    """``--blur-copies SIGMA``: the fit also sees a blurred copy of each good part (a softer lens is among what good
    parts look like); the model and its sidecar record it. ``--refit`` fits a model's variation model again."""
    import torch

    from model.draem.checkpoint import load_checkpoint

    data, model = trained(tmp_path, capsys)
    out = tmp_path / "v"
    assert main(["variation", "--model", str(model), "--data", str(data), "--blur-copies", "1.5",
                 "--out", str(out)]) == 0
    assert "and a blurred copy of each (up to 1.5 px)" in capsys.readouterr().out
    assert json.loads(out.with_suffix(".json").read_text())["train"]["variation"]["blur_copies_sigma"] == 1.5
    vm = load_checkpoint(out).detector.variation
    assert vm is not None and float(vm.blur_copies_sigma) == 1.5
    # --refit: a model that has a variation model fits it again, its networks unchanged (the shipped model with
    # copies, for a line with soft optics); without the flag, one line says how
    assert main(["variation", "--model", str(out), "--data", str(data), "--blur-copies", "0", "--refit",
                 "--out", str(tmp_path / "r")]) == 0
    before, after = load_checkpoint(out).detector, load_checkpoint(tmp_path / "r").detector
    assert after.variation is not None and float(after.variation.blur_copies_sigma) == 0.0
    assert not torch.equal(before.variation.mean, after.variation.mean)
    assert all(torch.equal(v, after.state_dict()[k]) for k, v in before.state_dict().items()
               if not k.startswith("variation."))
    assert main(["variation", "--model", str(out), "--data", str(data), "--out", str(tmp_path / "w")]) == 2
    assert "--refit" in capsys.readouterr().err
    for bad in ("-1", "nan"):  # one line naming the flag, before any loading
        refused_naming(capsys, "--blur-copies", bad, model, data, tmp_path / "w")


def test_global_polarization_takes_a_mode_records_it_and_refuses_an_unknown_one(tmp_path: Path, capsys) -> None:
    """``--global-polarization range`` (the shipped recipe, the default) fits the model to align only the
    polarization beyond its good parts' range and records the mode; the bare flag means ``mean``,
    ``--no-global-polarization`` ``off``; an unknown mode is one line naming the flag; a model without DoLP and AoLP
    is fitted plain by default."""
    from model.draem.checkpoint import load_checkpoint
    from model.draem.config import Alignment

    data, model = trained(tmp_path, capsys)
    for flags, mode in (([], Alignment.RANGE),  # the shipped recipe
                        (["--global-polarization", "range"], Alignment.RANGE),
                        (["--global-polarization"], Alignment.MEAN),
                        (["--no-global-polarization"], Alignment.OFF)):
        out = tmp_path / f"{mode.value}{len(flags)}"
        assert main(["variation", "--model", str(model), "--data", str(data), *flags, "--out", str(out)]) == 0
        said = capsys.readouterr().out
        assert ("aligned where beyond theirs" in said) == (mode is Alignment.RANGE)
        assert json.loads(out.with_suffix(".json").read_text())["train"]["variation"]["global_polarization"] == mode
        vm = load_checkpoint(out).detector.variation
        assert vm is not None and vm.polarization_alignment is mode
        assert (vm.polarization_range.tolist() == [1.0, 1.0, 0.0, 0.0]) == (mode is not Alignment.RANGE)
    with pytest.raises(SystemExit, match="2"):  # argparse's refusal
        main(["variation", "--model", str(model), "--data", str(data), "--global-polarization", "both",
              "--out", str(tmp_path / "w")])
    err = capsys.readouterr().err
    assert "--global-polarization" in err and "invalid choice" in err
    # a model without polarization priors gets the plain fit by default, not an error
    data, model = trained(tmp_path / "i", capsys, priors="intensity")
    assert main(["variation", "--model", str(model), "--data", str(data), "--out", str(tmp_path / "i" / "v")]) == 0
    vm = load_checkpoint(tmp_path / "i" / "v").detector.variation
    assert vm is not None and vm.polarization_alignment is Alignment.OFF


def test_clusters_and_the_contrast_range_are_recorded_as_fitted_and_a_negative_count_is_refused(
        tmp_path: Path, capsys) -> None:
    """``--clusters N``: the sidecar records how many clusters the fit kept, which is fewer when there are few good
    parts (one per 40; this set's ~30 make none, and the message then claims none); a negative count is one line
    naming the flag, before any loading. ``--contrast-range``: the sidecar records the good parts' range;
    ``--global-contrast`` (mean): that every frame's contrast is divided out."""
    data, model = trained(tmp_path, capsys)
    out = tmp_path / "c"
    assert main(["variation", "--model", str(model), "--data", str(data), "--clusters", "8", "--out", str(out)]) == 0
    assert "judged within" not in capsys.readouterr().out
    assert json.loads(out.with_suffix(".json").read_text())["train"]["variation"]["clusters"] == 0
    refused_naming(capsys, "--clusters", "-1", model, data, tmp_path / "w")
    assert main(["variation", "--model", str(model), "--data", str(data), "--contrast-range", "--out",
                 str(tmp_path / "k")]) == 0
    assert "contrast aligned where beyond theirs" in capsys.readouterr().out
    lo, hi = json.loads((tmp_path / "k.json").read_text())["train"]["variation"]["contrast_range"]
    assert 0.25 < lo <= hi < 4.0
    assert main(["variation", "--model", str(model), "--data", str(data), "--global-contrast", "--out",
                 str(tmp_path / "m")]) == 0
    assert "contrast aligned to theirs" in capsys.readouterr().out
    fitted = json.loads((tmp_path / "m.json").read_text())["train"]["variation"]
    assert fitted["global_contrast"] == "mean" and fitted["contrast_range"] == [1.0, 1.0]


def test_the_curvature_window_is_fitted_recorded_kept_by_a_refit_and_a_bad_sigma_is_refused(tmp_path: Path,
                                                                                           capsys) -> None:
    """``--curvature SIGMA``: the window statistic is each channel's curvature over SIGMA input px; the model file,
    its sidecar and the command's line say so, and a refit without the flag keeps the shipped recipe's. A negative,
    NaN or part-wide sigma is one line naming the flag, before any loading."""
    from model.draem.checkpoint import load_checkpoint
    from model.draem.variation import CURVATURE_SIGMA

    data, model = trained(tmp_path, capsys)
    out = tmp_path / "k"
    assert main(["variation", "--model", str(model), "--data", str(data), "--curvature", "3", "--out", str(out)]) == 0
    assert "its window each channel's curvature over 3 px" in capsys.readouterr().out
    assert json.loads(out.with_suffix(".json").read_text())["train"]["variation"]["curvature_sigma"] == 3.0
    vm = load_checkpoint(out).detector.variation
    assert vm is not None and float(vm.curvature_sigma) == 3.0
    assert main(["variation", "--model", str(out), "--data", str(data), "--refit", "--out", str(tmp_path / "r")]) == 0
    capsys.readouterr()
    vm = load_checkpoint(tmp_path / "r").detector.variation
    assert vm is not None and float(vm.curvature_sigma) == CURVATURE_SIGMA
    for bad in ("-1", "nan", "100"):
        refused_naming(capsys, "--curvature", bad, model, data, tmp_path / "w")


def test_the_smooth_field_is_taken_out_when_asked_recorded_and_said(tmp_path: Path, capsys) -> None:
    """``--smooth-field``: the variation model takes a lens's smooth field out of every frame's residual
    (``model.draem.smooth_field``); the file, its sidecar and the command's line say so. Without the flag the shipped
    recipe's (none)."""
    from model.draem.checkpoint import load_checkpoint

    data, model = trained(tmp_path, capsys)
    for flag, on in (("--smooth-field", True), ("--no-smooth-field", False)):
        out = tmp_path / flag
        assert main(["variation", "--model", str(model), "--data", str(data), flag, "--out", str(out)]) == 0
        assert ("a lens's smooth field taken out" in capsys.readouterr().out) is on
        assert json.loads(out.with_suffix(".json").read_text())["train"]["variation"]["smooth_field"] is on
        vm = load_checkpoint(out).detector.variation
        assert vm is not None and vm.takes_smooth_field is on


def test_a_second_look_without_its_test_is_recorded_and_said(tmp_path: Path, capsys) -> None:
    """``--no-second-look-test``: the second look only gates the parts a look network is asked about; the file, its
    sidecar and the command's line say so (this set's ~30 good parts make 20 or more references)."""
    from model.draem.checkpoint import load_checkpoint

    data, model = trained(tmp_path, capsys)
    out = tmp_path / "g"
    assert main(["variation", "--model", str(model), "--data", str(data), "--no-second-look-test",
                 "--out", str(out)]) == 0
    assert "a second look's gate only" in capsys.readouterr().out
    assert json.loads(out.with_suffix(".json").read_text())["train"]["variation"]["second_look_test"] is False
    vm = load_checkpoint(out).detector.variation
    assert vm is not None and vm.second_look.references and not vm.second_look.testing


def test_judged_priors_fit_a_judge_of_some_priors_alone_and_a_prior_the_model_lacks_is_refused(
        tmp_path: Path, capsys) -> None:
    """``--judged-priors aolp``: the window is taken over AoLP's channels only (intensity still registers the part),
    recorded in the model and its sidecar; a prior the model does not read is refused in one line naming the flag."""
    from model.draem.checkpoint import load_checkpoint

    data, model = trained(tmp_path, capsys)
    out = tmp_path / "v"
    assert main(["variation", "--model", str(model), "--data", str(data), "--judged-priors", "aolp",
                 "--out", str(out)]) == 0
    assert "judging aolp only" in capsys.readouterr().out
    assert json.loads(out.with_suffix(".json").read_text())["train"]["variation"]["judged_priors"] == ["aolp"]
    vm = load_checkpoint(out).detector.variation
    assert vm is not None and vm.judged_channels.tolist() == [0.0, 0.0, 1.0, 1.0]
    for bad in ("normal", ""):
        refused_naming(capsys, "--judged-priors", bad, model, data, tmp_path / "w")


def test_threshold_gives_a_file_without_a_turn_centre_its_good_parts_median_turn(tmp_path: Path, capsys) -> None:
    """A variation fit reads its good parts' median turn (``turn_centre``); a file fitted before that has none, and
    its parts read no turn. ``station threshold`` on a split of the line's good parts gives it theirs, keeps the
    threshold it would choose anyway, and says so; the station's parts then read their turn from it."""
    import math

    import torch

    from model.draem.checkpoint import load_checkpoint, save_checkpoint

    data, model = trained(tmp_path, capsys)
    out = tmp_path / "v"
    assert main(["variation", "--model", str(model), "--data", str(data), "--out", str(out)]) == 0
    ck = load_checkpoint(out)
    fitted_centre = float(ck.detector.variation.turn_centre)
    assert math.isfinite(fitted_centre) and abs(fitted_centre) < 5.0  # the line set's parts are not turned
    ck.detector.variation.turn_centre.fill_(math.nan)  # as a file fitted before 2026-12-06
    meta = ck.meta
    save_checkpoint(out, ck.detector, ck.threshold, meta["threshold_rule"], meta.get("data_manifest_sha256"),
                    meta.get("metrics"), meta.get("train", {}))
    old = load_checkpoint(out)
    x = torch.zeros(1, *old.detector.variation.mean.shape) + old.detector.variation.mean[None]
    assert torch.isnan(old.detector.variation.zmaps(x).turn_deg).all()
    capsys.readouterr()
    assert main(["threshold", "--model", str(out), "--data", str(data)]) == 0
    line = capsys.readouterr().out
    assert "its good parts' median turn" in line and "degrees from the reference" in line
    new = load_checkpoint(out)
    assert math.isfinite(float(new.detector.variation.turn_centre))
    assert abs(float(new.detector.variation.turn_centre) - fitted_centre) < 2.0
    assert new.threshold == pytest.approx(ck.threshold, rel=1e-4)
