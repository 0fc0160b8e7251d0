"""``station ensemble``: single-prior models trained apart, assembled into the paper's ensemble, thresholded on
the validation split, carrying the normal member's estimator, and read by ``station eval --ablation``."""

from __future__ import annotations

import json
from pathlib import Path

import torch
from test_run import make_dataset, make_model  # same folder (pytest puts it on sys.path)

from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.normals.estimator import NormalEstimator, describe
from model.normals.net import NormalNetConfig, NormalUNet, save_normal_net
from station.cli import main
from station.model_detector import DraemDetector


def normal_member(folder: Path) -> Path:
    """A fused model over the learned normal prior, its estimator beside it as ``station train`` leaves it."""
    save_normal_net(folder / "normal_net", NormalUNet(NormalNetConfig(base_width=4, levels=2, input_size_px=32)))
    det = Detector(ModelConfig.from_preset("tiny", ("normal",), "fused", 32))
    det.init_weights(torch.Generator().manual_seed(5))
    save_checkpoint(folder / "last", det, 0.5, "test",
                    train={"normal_prior": describe(NormalEstimator.load(folder / "normal_net", None))})
    return folder / "last"


def test_ensemble_from_members_trained_apart(tmp_path: Path, capsys) -> None:
    data = make_dataset(tmp_path / "ds", n=30, defective=lambda i: i == 12)  # val: 2, 12, 22
    r, a = make_model(tmp_path / "r" / "last", ("intensity",)), make_model(tmp_path / "a" / "last", ("aolp",))
    n = normal_member(tmp_path / "n")
    out = tmp_path / "ens" / "last"
    assert main(["ensemble", "--members", f"{r},{a},{n}", "--data", str(data), "--out", str(out)]) == 0
    assert "threshold" in capsys.readouterr().out
    ck = load_checkpoint(out)
    assert ck.detector.config.priors == ("intensity", "aolp", "normal") and ck.threshold is not None
    meta = ck.meta["train"]
    assert meta["assembled_from"]["aolp"]["model"] == str(a)
    assert meta["normal_prior"]["file"] == "normal_net.json" and (out.parent / "normal_net.pt").is_file()
    DraemDetector(out, "cpu", "fp32")  # the station loads it, normal estimator included

    assert main(["eval", "--model", str(out), "--data", str(data), "--split", "val", "--ablation", "--no-plots",
                 "--no-synthetic", "--out", str(tmp_path / "ev")]) == 0
    rows = json.loads((tmp_path / "ev" / "eval.json").read_text())["ablation"]
    assert [row["priors"] for row in rows] == ["R", "R+AoLP"]  # no DoLP member: the ablation stops there


def test_ensemble_refuses_a_multi_prior_member_and_overwriting_a_member(tmp_path: Path, capsys) -> None:
    data = make_dataset(tmp_path / "ds", n=10)
    r, ra = make_model(tmp_path / "r" / "last", ("intensity",)), make_model(tmp_path / "ra" / "last",
                                                                            ("intensity", "aolp"))
    assert main(["ensemble", "--members", f"{r},{ra}", "--data", str(data), "--out", str(tmp_path / "e")]) == 2
    assert f"{ra}: its network 'fused' reads 2 priors" in capsys.readouterr().err
    assert main(["ensemble", "--members", f"{r},{ra}", "--data", str(data), "--out", str(r)]) == 2
    assert "would overwrite one of the members" in capsys.readouterr().err
    assert not (tmp_path / "e.json").exists()
