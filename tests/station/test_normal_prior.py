"""The learned normal prior from training to the station: ``station train --normal-net`` copies the estimator
beside the checkpoint, and the station feeds the DRAEM the same normals (and every other channel) as training."""

from __future__ import annotations

import json
import shutil
import sqlite3
from pathlib import Path

import numpy as np
import pytest
import torch
from test_run import make_dataset, write_config

from drivers.frame import Frame
from model.draem.predictor import PRIOR_MAPS
from model.normals.estimator import MAP_NAMES
from model.normals.net import NormalNetConfig, NormalUNet, save_normal_net
from model.priors.conventions import IMX250MZR
from station.cli import main
from station.datasets import load_split
from station.inspector import Inspector
from station.model_detector import DraemDetector, ModelLoadError


@pytest.fixture(scope="module")
def trained(tmp_path_factory) -> tuple[Path, Path, Path]:
    """(dataset, normal net stem, DRAEM output folder) after a 2-step ``station train`` over intensity + normal."""
    tmp = tmp_path_factory.mktemp("normal_prior")
    ds = make_dataset(tmp / "ds")
    torch.manual_seed(0)
    net = NormalUNet(NormalNetConfig(base_width=4, levels=2, input_size_px=32))
    with torch.no_grad():
        net.head.weight.normal_(std=0.5)  # the head starts at zero (normals = view): make the output depend on it
    save_normal_net(tmp / "nets" / "my_net", net)
    out = tmp / "train"
    assert main(["train", "--data", str(ds), "--priors", "intensity,normal", "--preset", "tiny", "--fusion", "fused",
                 "--size", "32", "--steps", "2", "--batch-size", "2", "--eval-every", "2", "--device", "cpu",
                 "--normal-net", str(tmp / "nets" / "my_net"), "--out", str(out)]) == 0
    return ds, tmp / "nets" / "my_net", out


@pytest.fixture(scope="module")
def trained_band(trained, tmp_path_factory) -> Path:
    """The same over the band across the middle of the frame (``roi = "band"``, the shipped model's region): the
    estimator reads its centre square, and the band is cut from it."""
    _, net_stem, _ = trained
    tmp = tmp_path_factory.mktemp("normal_prior_band")
    ds = make_dataset(tmp / "ds", 20, defective=lambda i: i % 2 == 1 or i == 12)  # val: a good part and a defect
    out = tmp / "train"
    assert main(["train", "--data", str(ds), "--priors", "intensity,normal", "--preset", "tiny", "--fusion", "fused",
                 "--size", "32", "--roi", "band", "--steps", "2", "--batch-size", "2", "--eval-every", "2",
                 "--device", "cpu", "--normal-net", str(net_stem), "--out", str(out)]) == 0
    return out


def test_checkpoint_names_its_estimator_and_carries_a_copy(trained) -> None:
    _, net_stem, out = trained
    record = json.loads((out / "best.json").read_text())["train"]["normal_prior"]
    original = json.loads(net_stem.with_suffix(".json").read_text())
    assert record["source"] == "learned" and record["file"] == "normal_net.json"
    assert record["weights_sha256"] == original["weights_sha256"]  # the copy holds the same weights
    assert (out / "normal_net.pt").is_file() and PRIOR_MAPS["normal"] == MAP_NAMES
    assert json.loads((out / "last.json").read_text())["train"]["normal_prior"] == record  # the final step too


def test_eval_refuses_a_normal_model_that_does_not_say_where_its_normals_came_from(trained, tmp_path, capsys) -> None:
    ds, _, out = trained
    meta = json.loads((out / "last.json").read_text())
    del meta["train"]["normal_prior"]
    (tmp_path / "last.json").write_text(json.dumps(meta))
    (tmp_path / "last.pt").write_bytes((out / "last.pt").read_bytes())
    assert main(["eval", "--model", str(tmp_path / "last"), "--data", str(ds), "--no-plots",
                 "--out", str(tmp_path / "e")]) == 2
    assert "does not record how that was made" in capsys.readouterr().err


@pytest.mark.parametrize("roi", ["center", "band"])
def test_station_feeds_the_model_what_training_fed_it(roi, trained, request) -> None:
    ds = trained[0]
    out = trained[2] if roi == "center" else request.getfixturevalue("trained_band")
    det = DraemDetector(out / "best", device="cpu")
    assert det.normals is not None and set(det.priors) == set(MAP_NAMES) and det.config.roi == roi
    sp = load_split(ds, "test", det.config.priors, det.config.input_shape, progress=False, roi=roi,
                    normals=det.normals)
    seen = []
    predict = det.net.predict
    det.net.predict = lambda x, **kw: seen.append(x.detach().clone()) or predict(x, **kw)
    inspector = Inspector(det, IMX250MZR)
    from sim.dataset import open_dataset

    d = open_dataset(ds)
    for k, i in enumerate(sp.index):
        s = d.load(i)
        res = inspector.inspect(Frame(s.raw, "Mono8", 8, k, 0, 0))
        assert res.error is None and 0.0 <= res.score <= 1.0
    x = torch.cat(seen)
    normal = x[:, 1:4]
    assert torch.allclose(normal.norm(dim=1), torch.ones(1), atol=1e-3)
    assert float(normal[:, 2].std()) > 1e-3  # the estimator's normals, not a constant "facing the camera"
    assert torch.allclose(x, sp.priors, atol=1e-4), float((x - sp.priors).abs().max())


def test_station_runs_a_normal_model_and_refuses_bad_estimators(trained, tmp_path, capsys) -> None:
    ds, _, out = trained
    model = tmp_path / "m"
    shutil.copytree(out, model)
    cfg = write_config(tmp_path, model / "best", ds)
    assert main(["run", "--camera", "sim", "--config", str(cfg), "--frames", "3"]) == 0
    rows = sqlite3.connect(tmp_path / "log.sqlite").execute("SELECT decision, score FROM inspections").fetchall()
    assert len(rows) == 3 and all(d in ("pass", "reject") and 0 <= s <= 1 for d, s in rows)

    (model / "normal_net.pt").write_bytes(b"not weights")
    with pytest.raises(ModelLoadError, match=r"normal_net\.pt"):
        DraemDetector(model / "best", device="cpu")
    (model / "normal_net.pt").unlink()
    with pytest.raises(ModelLoadError, match=r"normal_net\.pt: weights file missing"):
        DraemDetector(model / "best", device="cpu")


def test_ground_truth_normals_train_but_do_not_run(tmp_path) -> None:
    ds = make_dataset(tmp_path / "ds")
    from sim.dataset import open_dataset

    d = open_dataset(ds)
    for i in d.indices():  # the test set has no rendered normals: give it some
        sd = tmp_path / "ds" / "samples" / f"{i:06d}"
        assert (sd / "gt.npz").is_file()
        with np.load(sd / "gt.npz") as f:
            arrays = dict(f)
        n = np.zeros((*arrays["object_mask"].shape, 3), np.float32)
        n[..., 2] = 1
        arrays["normal"] = n
        np.savez(sd / "gt.npz", **arrays)
    assert main(["train", "--data", str(ds), "--priors", "intensity,normal", "--preset", "tiny", "--fusion", "fused",
                 "--size", "32", "--steps", "1", "--batch-size", "2", "--eval-every", "1", "--device", "cpu",
                 "--out", str(tmp_path / "t")]) == 0
    record = json.loads((tmp_path / "t" / "best.json").read_text())["train"]["normal_prior"]
    assert record == {"source": "ground truth"}
    with pytest.raises(ModelLoadError, match="ground truth, not a learned normal estimator"):
        DraemDetector(tmp_path / "t" / "best", device="cpu")


def test_lens_field_of_view_overrides_the_training_sets(trained) -> None:
    _, _, out = trained
    rng = np.random.default_rng(0)
    maps = {k: rng.random((48, 64)).astype(np.float32) for k in MAP_NAMES}
    default = DraemDetector(out / "best", device="cpu")
    wide = DraemDetector(out / "best", device="cpu", fov_x_deg=60.0)
    assert default.normals.fov_x_deg is None and wide.normals.fov_x_deg == 60.0  # the test set has no fov: ortho
    a, b = default.normals.predict_frame(maps), wide.normals.predict_frame(maps)
    assert np.abs(a - b).max() > 1e-3  # other viewing directions, other normals


def test_a_variation_model_fitted_elsewhere_carries_the_estimator(trained, tmp_path) -> None:
    """``station variation --out`` in another folder: the new checkpoint needs its normal estimator beside it (it
    was left behind, so ``station eval`` refused the file: "normal_net.json: normal-estimator sidecar missing")."""
    _, _, out = trained
    ds = make_dataset(tmp_path / "ds", 40)  # enough good parts to fit
    assert main(["variation", "--model", str(out / "best"), "--data", str(ds), "--out",
                 str(tmp_path / "elsewhere" / "v")]) == 0
    det = DraemDetector(tmp_path / "elsewhere" / "v", device="cpu")
    assert det.normals is not None
