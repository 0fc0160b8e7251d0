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
from station.commands.eval import load_and_evaluate


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
    assert "5.00%" in json.loads(model.with_suffix(".json").read_text())["threshold_rule"]
    for k, v in before.detector.state_dict().items():  # the weights are untouched
        assert torch.equal(v, after.detector.state_dict()[k])
    assert "threshold" in capsys.readouterr().out


def test_threshold_refuses_a_val_split_without_defects_or_another_training_set(tmp_path: Path, capsys) -> None:
    data = make_dataset(tmp_path / "ds", n=20)  # val: 2, 12, both good
    model = make_model(tmp_path / "m" / "last", ("intensity",))
    assert main(["threshold", "--model", str(model), "--data", str(data)]) == 2
    assert "needs good and defective parts" in capsys.readouterr().err
    ck = load_checkpoint(model)
    save_checkpoint(model, ck.detector, 0.5, "test", data_manifest_sha256="0" * 64)
    assert main(["threshold", "--model", str(model), "--data", str(data)]) == 2
    assert "trained on another set" in capsys.readouterr().err
