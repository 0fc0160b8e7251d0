"""``station import`` / ``station export``: the MVTec AD layout both ways, bit depths, sets without masks, and the
commands that read an imported set (eval, threshold)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import cv2
import numpy as np
import pytest
from line_sets import make_line_set, make_model  # same folder (pytest puts it on sys.path)

from sim.dataset import open_dataset
from station.cli import main
from station.errors import UserError


def _by_source(root: Path) -> dict[str, object]:
    ds = open_dataset(root)
    return {Path(ds.load(i).params["source"]["file"]).stem: ds.load(i) for i in ds.indices()}


def test_export_then_import_gives_back_the_same_raw_masks_and_splits(tmp_path: Path, capsys) -> None:
    src = make_line_set(tmp_path / "ds", n=30, bit_depth=12, defective=lambda i: i % 5 == 2)
    assert main(["export", "--data", str(src), "--out", str(tmp_path / "mv")]) == 0
    assert "exported 30 samples" in capsys.readouterr().out  # 2 defective train samples go to test/
    assert sorted(p.name for p in (tmp_path / "mv").iterdir()) == [
        "ground_truth", "object_masks", "polar_ano.json", "test", "train", "val"]
    assert main(["import", "--from", str(tmp_path / "mv"), "--out", str(tmp_path / "back")]) == 0  # no flags
    out = capsys.readouterr().out
    assert "12-bit" in out and "defect masks for 6 of 6" in out
    orig, back = open_dataset(src), _by_source(tmp_path / "back")
    assert len(back) == 30 and open_dataset(tmp_path / "back").manifest["bit_depth"] == 12
    for i in orig.indices():
        a, b = orig.load(i), back[f"{i:06d}"]
        assert b.raw.dtype == a.raw.dtype and np.array_equal(a.raw, b.raw)
        assert np.array_equal(a.defect_mask, b.defect_mask) and np.array_equal(a.object_mask, b.object_mask)
        moved = orig.split(i) == "train" and a.label  # MVTec's train/ is good parts only
        assert (b.label, b.split) == (a.label, "test" if moved else orig.split(i))  # from the folders
    assert open_dataset(tmp_path / "back").indices("val") != orig.indices("val")  # renumbered, same parts
    assert main(["import", "--from", str(tmp_path / "mv"), "--out", str(tmp_path / "back")]) == 2
    assert "not an empty folder" in capsys.readouterr().err


def _write_mvtec(root: Path, dtype=np.uint16, top: int = 4000, masks: bool = False) -> Path:
    rng = np.random.default_rng(0)
    for folder, n in (("train/good", 12), ("test/good", 3), ("test/scratch", 3)):
        (root / folder).mkdir(parents=True)
        for k in range(n):
            img = rng.integers(0, top, (64, 96)).astype(dtype)
            cv2.imwrite(str(root / folder / f"img{k}.png"), img)
            if masks and "scratch" in folder:
                (root / "ground_truth/scratch").mkdir(parents=True, exist_ok=True)
                m = np.zeros((64, 96), np.uint8)
                m[10:20, 10:20] = 255
                cv2.imwrite(str(root / "ground_truth/scratch" / f"img{k}_mask.png"), m)
    return root


def test_wrong_bit_depth_is_one_line_naming_the_file(tmp_path: Path, capsys) -> None:
    src = _write_mvtec(tmp_path / "mv", top=5000)  # codes up to 4999: not 12-bit
    assert main(["import", "--from", str(src), "--out", str(tmp_path / "a"), "--bit-depth", "12"]) == 2
    lines = [ln for ln in capsys.readouterr().err.splitlines() if "error" in ln]  # (the rest: progress bar)
    assert len(lines) == 1 and "exceeds the 12-bit range" in lines[0]
    assert lines[0].startswith(f"station import: error: {src / 'train' / 'good' / 'img0.png'}: code ")
    assert not (tmp_path / "a").exists()
    assert main(["import", "--from", str(src), "--out", str(tmp_path / "a")]) == 2  # 16-bit files need the depth
    assert "pass --bit-depth" in capsys.readouterr().err
    dark = _write_mvtec(tmp_path / "dark", top=4096)  # 12-bit codes, declared 16-bit: the 16x-too-dark trap
    assert main(["import", "--from", str(dark), "--out", str(tmp_path / "b"), "--bit-depth", "16"]) == 2
    err = capsys.readouterr().err
    assert "fits 12 bits" in err and "16x too dark" in err and "img" in err
    assert main(["import", "--from", str(dark), "--out", str(tmp_path / "b"), "--bit-depth", "12"]) == 0


def test_a_set_without_masks_evaluates_image_level_only_and_sets_a_threshold(tmp_path: Path, capsys) -> None:
    src = _write_mvtec(tmp_path / "mv", dtype=np.uint8, top=200)
    assert main(["import", "--from", str(src), "--out", str(tmp_path / "ds")]) == 0
    out = capsys.readouterr().out
    assert "8-bit" in out and "no defect masks: image-level metrics only" in out and "no object masks" in out
    ds = open_dataset(tmp_path / "ds")
    assert [len(ds.indices(s)) for s in ("train", "val", "test")] == [11, 1, 6]  # val: 10 % of train/good
    model = make_model(tmp_path / "m" / "best")
    assert main(["eval", "--model", str(model), "--data", str(tmp_path / "ds"), "--no-plots", "--no-synthetic",
                 "--out", str(tmp_path / "ev")]) == 0
    rep = json.loads((tmp_path / "ev" / "eval.json").read_text())
    row = rep["rows"][0]
    assert (row["n"], row["anomalous"], row["with_mask"]) == (6, 3, 0)
    assert row["pixel_auroc"] is None or np.isnan(row["pixel_auroc"])  # never scored against all-zero masks
    assert "image-level metrics only" in rep["pixel_metrics_scope"]
    # station threshold on a set it was not trained on, a split with good parts only
    assert main(["threshold", "--model", str(model), "--data", str(tmp_path / "ds"), "--split", "train"]) == 0
    assert "no defective parts there" in capsys.readouterr().out
    side = json.loads(model.with_suffix(".json").read_text())
    used = side["train"]["threshold_set"]  # noise frames: the presence check calls some of them empty
    assert used["n_good"] + len(used["left_out"]) == 11 and used["n_good"] >= 5 and side["threshold"] != 0.5


def test_masks_for_some_defects_restrict_pixel_metrics_to_those(tmp_path: Path) -> None:
    src = _write_mvtec(tmp_path / "mv", dtype=np.uint8, top=200, masks=True)
    (src / "ground_truth/scratch/img0_mask.png").unlink()
    assert main(["import", "--from", str(src), "--out", str(tmp_path / "ds")]) == 0
    model = make_model(tmp_path / "m" / "best")
    assert main(["eval", "--model", str(model), "--data", str(tmp_path / "ds"), "--no-plots", "--no-synthetic",
                 "--out", str(tmp_path / "ev")]) == 0
    rep = json.loads((tmp_path / "ev" / "eval.json").read_text())
    assert rep["rows"][0]["with_mask"] == 2 and "2 of 3 defective parts" in rep["pixel_metrics_scope"]
    assert 0.0 <= rep["rows"][0]["pixel_auroc"] <= 1.0


@pytest.mark.parametrize("bad", ["train/scratch", "nothing"])
def test_a_folder_that_is_not_the_layout_is_refused(tmp_path: Path, capsys, bad: str) -> None:
    (tmp_path / "mv" / bad).mkdir(parents=True)
    assert main(["import", "--from", str(tmp_path / "mv"), "--out", str(tmp_path / "ds")]) == 2
    assert ("good parts only" if bad == "train/scratch" else "not an MVTec AD layout") in capsys.readouterr().err


def test_train_reads_an_imported_set_and_records_its_frame_statistics(tmp_path: Path) -> None:
    src = _write_mvtec(tmp_path / "mv", dtype=np.uint8, top=200)
    assert main(["import", "--from", str(src), "--out", str(tmp_path / "ds")]) == 0
    out = tmp_path / "train"
    assert main(["train", "--data", str(tmp_path / "ds"), "--priors", "intensity,aolp", "--preset", "tiny",
                 "--fusion", "fused", "--size", "32", "--steps", "2", "--batch-size", "2", "--eval-every", "2",
                 "--device", "cpu", "--out", str(out)]) == 0
    for name in ("best", "last"):
        stats = json.loads((out / f"{name}.json").read_text())["train"]["frame_statistics"]
        assert stats["n_frames"] == 11 and 0.0 < stats["median"]["median_level"] < 1.0 and "q1" in stats


@pytest.mark.parametrize(("text", "message"), [
    ("[]", "expected a JSON object"),
    ('{"layout": ["imx250mzr"]}', "layout: expected a string"),
    ('{"bit_depth": "12"}', "bit_depth: expected an integer"),
    ('{"bit_depth": 12', "unreadable"),
])
def test_a_bad_polar_ano_json_is_one_line_naming_it(tmp_path: Path, text: str, message: str) -> None:
    """A list, a truncated file or a key of the wrong type printed a traceback (import and capture)."""
    from station.mvtec import read_info

    src = _write_mvtec(tmp_path / "mv", dtype=np.uint8, top=200)
    (src / "polar_ano.json").write_text(text)
    with pytest.raises(UserError, match=rf"polar_ano.json: .*{message}"):
        read_info(src)
    r = subprocess.run([sys.executable, "-m", "station.cli", "import", "--from", str(src), "--out",
                        str(tmp_path / "ds")], capture_output=True, text=True)
    assert r.returncode == 2 and "Traceback" not in r.stderr and "polar_ano.json" in r.stderr
