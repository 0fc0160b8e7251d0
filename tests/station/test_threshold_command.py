"""``station threshold``: a checkpoint's threshold set on its set's validation split, by the training rule."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import torch
from test_run import make_dataset, make_model  # same folder (pytest puts it on sys.path)

from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.metrics import choose_threshold
from station.cli import main
from station.datasets import manifest_sha256
from station.evaluation import load_and_evaluate


def test_threshold_is_chosen_on_val_and_written_to_the_sidecar(tmp_path: Path, capsys) -> None:
    data = make_dataset(tmp_path / "ds", n=30, defective=lambda i: i == 12)  # val: 2, 12, 22
    model = make_model(tmp_path / "m" / "last", ("intensity", "aolp"))
    before = load_checkpoint(model)
    assert before.threshold == 0.5
    assert main(["threshold", "--model", str(model), "--data", str(data)]) == 0
    after = load_checkpoint(model)
    _, _, sp, _, ev = load_and_evaluate(str(model), data, "val")
    assert sp.label.tolist() == [0, 1, 0]
    expected = choose_threshold(sp.label.numpy(), ev.scores)
    assert after.threshold == pytest.approx(expected.threshold) and after.threshold != 0.5
    assert "1.00%" in json.loads(model.with_suffix(".json").read_text())["threshold_rule"]
    for k, v in before.detector.state_dict().items():  # the weights are untouched
        assert torch.equal(v, after.detector.state_dict()[k])
    # what 0 of the 2 good parts above it says of new good parts: up to 1 - 0.05 ** (1 / 2), 77.6 %
    assert "(0 of 2; new good parts: about 33.3 %, at most 77.6 % at 95 % confidence)" in capsys.readouterr().out


def test_threshold_takes_good_parts_only_and_other_sets_but_not_the_training_split(tmp_path: Path, capsys) -> None:
    data = make_dataset(tmp_path / "ds", n=20)  # val: 2, 12, both good
    model = make_model(tmp_path / "m" / "last", ("intensity",))
    ck = load_checkpoint(model)
    save_checkpoint(model, ck.detector, 0.5, "test", data_manifest_sha256=manifest_sha256(data))  # trained on data
    assert main(["threshold", "--model", str(model), "--data", str(data)]) == 0  # good parts bound false rejects
    assert "no defective parts there" in capsys.readouterr().out
    assert "threshold_set" not in load_checkpoint(model).meta["train"]  # its own training set: nothing to record
    save_checkpoint(model, ck.detector, 0.5, "test", data_manifest_sha256="0" * 64)  # "trained on another set"
    assert main(["threshold", "--model", str(model), "--data", str(data)]) == 0
    assert "not its training set" in capsys.readouterr().out
    meta = load_checkpoint(model).meta
    assert meta["train"]["threshold_set"]["split"] == "val" and meta["data_manifest_sha256"] == "0" * 64
    assert (meta["train"]["threshold_set"]["n_good"], meta["train"]["threshold_set"]["n_good_flagged"]) == (2, 0)
    save_checkpoint(model, ck.detector, 0.5, "test", data_manifest_sha256=manifest_sha256(data))
    assert main(["threshold", "--model", str(model), "--data", str(data), "--split", "train"]) == 2
    assert "not held out" in capsys.readouterr().err


def test_frames_the_station_would_not_judge_set_no_threshold(tmp_path: Path, capsys) -> None:
    """A black frame among the good parts (no part in view: the station logs it empty) used to count as a good
    part, and its high score set the threshold: every defective part passed."""
    from line_sets import make_line_set

    from sim.dataset import open_dataset

    data = make_line_set(tmp_path / "ds", 60, defective=lambda i: False, blank=lambda i: i in (2, 12))
    val = open_dataset(data).indices("val")
    assert {2, 12} <= set(val)
    model = make_model(tmp_path / "m" / "last", ("intensity", "aolp"))
    assert main(["threshold", "--model", str(model), "--data", str(data)]) == 0
    out = capsys.readouterr().out
    assert "left out 2 frames the station would not judge" in out and "sample 2: no part in view" in out
    meta = load_checkpoint(model).meta
    assert meta["train"]["threshold_set"]["n_good"] == len(val) - 2
    assert meta["train"]["threshold_set"]["left_out"] == {"2": "no part in view", "12": "no part in view"}


def test_the_cameras_presence_rule_decides_which_frames_set_no_threshold(tmp_path: Path, capsys) -> None:
    """A camera looking level at the part uses the row rule at the station (``[presence] rule``); its threshold
    must leave out the frames that rule calls empty, not the DoLP rule's."""
    from line_sets import make_line_set

    data = make_line_set(tmp_path / "ds", 60, defective=lambda i: False, blank=lambda i: i == 2,
                         polar_only=lambda i: i == 12)
    model = make_model(tmp_path / "m" / "last", ("intensity", "aolp"))
    assert main(["threshold", "--model", str(model), "--data", str(data)]) == 0
    assert load_checkpoint(model).meta["train"]["threshold_set"]["left_out"] == {"2": "no part in view"}
    capsys.readouterr()
    assert main(["threshold", "--model", str(model), "--data", str(data), "--presence-rule", "row_contrast"]) == 0
    assert "left out 2 frames" in capsys.readouterr().out
    threshold_set = load_checkpoint(model).meta["train"]["threshold_set"]
    assert threshold_set["left_out"] == {"2": "no part in view", "12": "no part in view"}
    assert threshold_set["presence_rule"] == "row_contrast"


def test_a_promise_the_split_cannot_keep_is_refused_in_one_line(tmp_path: Path, capsys) -> None:
    data = make_dataset(tmp_path / "ds", n=30, defective=lambda i: i == 12)  # val: 2 good parts
    model = make_model(tmp_path / "m" / "last", ("intensity",))
    assert main(["threshold", "--model", str(model), "--data", str(data), "--confidence", "0.95"]) == 2
    last = capsys.readouterr().err.strip().splitlines()[-1]  # the progress bar's lines come before it
    assert "split 'val': 2 good parts cannot promise at most 1.00% of new good parts rejected at 95% confidence: " \
           "that needs 299 or more" in last and str(data) in last
    assert load_checkpoint(model).threshold == 0.5  # nothing written
    assert main(["threshold", "--model", str(model), "--data", str(data), "--confidence", "1.5"]) == 2
    assert "--confidence 1.5: a fraction in (0, 1)" in capsys.readouterr().err
    # a rate the two good parts can promise at 95 %: none above the threshold (1 - 0.05 ** 0.5 = 77.6 %)
    assert main(["threshold", "--model", str(model), "--data", str(data), "--confidence", "0.95",
                 "--max-good-flagged", "0.8"]) == 0
    assert "at 95% confidence (0 of 2 above)" in load_checkpoint(model).meta["threshold_rule"]


def test_threshold_on_several_sets_pools_their_parts(tmp_path: Path, capsys) -> None:
    """Good parts captured on two days, or rendered with two seeds: the threshold is the rule's on all of them, and
    the sidecar names both sets."""
    import numpy as np

    a = make_dataset(tmp_path / "a", n=30, defective=lambda i: i == 12)  # val: 2, 12, 22
    b = make_dataset(tmp_path / "b", n=30, defective=lambda i: i == 2)
    model = make_model(tmp_path / "m" / "last", ("intensity", "aolp"))
    assert main(["threshold", "--model", str(model), "--data", str(a), str(b)]) == 2  # both of seed 0
    assert "the same seed (0) holds the same parts" in capsys.readouterr().err.splitlines()[-1]
    manifest = json.loads((b / "manifest.json").read_text())
    (b / "manifest.json").write_text(json.dumps({**manifest, "seed": 1}))  # the fixture draws both alike
    assert main(["threshold", "--model", str(model), "--data", str(a), str(b)]) == 0
    assert f"on 6 val parts of {a}, {b} (2 sets pooled; recorded in the sidecar)" in capsys.readouterr().out
    scores, labels = [], []
    for d in (a, b):
        _, _, sp, _, ev = load_and_evaluate(str(model), d, "val")
        scores.append(np.asarray(ev.scores))
        labels.append(sp.label.numpy())
    expected = choose_threshold(np.concatenate(labels), np.concatenate(scores))
    meta = load_checkpoint(model).meta
    assert meta["threshold"] == pytest.approx(expected.threshold)
    record = meta["train"]["threshold_set"]
    assert record["data"] == [str(a), str(b)] and len(record["manifest_sha256"]) == 2
    assert (record["n_good"], record["n_defective"]) == (4, 2)
    assert main(["threshold", "--model", str(model), "--data", str(a), str(tmp_path / "a")]) == 2
    assert "a set is named twice" in capsys.readouterr().err.splitlines()[-1]


def test_concat_joins_splits_in_order_and_fills_a_missing_mask_known() -> None:
    """``station.datasets.concat``: tensors and per-sample lists joined in order; a split without ``mask_known``
    (every mask ground truth) next to one with it counts as all known; object masks known only if in every split."""
    from station.datasets import SplitTensors, concat

    def split(n: int, first: int, known=None, objects: bool = True) -> SplitTensors:
        return SplitTensors(torch.full((n, 1, 2, 2), float(first)), torch.ones(n, 2, 2), torch.zeros(n, 2, 2),
                            torch.arange(n) % 2, ["stain" if i % 2 else "" for i in range(n)],
                            list(range(first, first + n)), known, object_masks_known=objects,
                            unjudged=[None] * n)

    both = concat([split(2, 0), split(3, 10, torch.tensor([True, False, True]), objects=False)])
    assert both.index == [0, 1, 10, 11, 12] and both.priors[:, 0, 0, 0].tolist() == [0, 0, 10, 10, 10]
    assert both.mask_known.tolist() == [True, True, True, False, True] and not both.object_masks_known
    assert both.label.tolist() == [0, 1, 0, 1, 0] and both.defect_type == ["", "stain", "", "stain", ""]
    assert concat([split(1, 0), split(1, 5)]).mask_known is None and len(both.unjudged) == 5
