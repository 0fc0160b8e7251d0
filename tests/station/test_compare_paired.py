"""``station compare --paired``: two models' image AUROC on the same parts, the gain and its paired bootstrap SE,
from ``station eval``'s ``scores.csv``; reports on other parts or without scores are refused in one line."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np

from station.cli import main


def report(folder: Path, labels: np.ndarray, types: list[str], scores: np.ndarray) -> Path:
    folder.mkdir(parents=True)
    with open(folder / "scores.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["index", "label", "defect_type", "score", "variation"])
        for i, (y, t, s) in enumerate(zip(labels, types, scores, strict=True)):
            w.writerow([i, int(y), t, s, s])
    return folder


def test_paired_gain_and_its_standard_error_per_type(tmp_path: Path, capsys) -> None:
    rng = np.random.default_rng(0)
    labels = np.r_[np.zeros(100), np.ones(60)].astype(int)
    types = [""] * 100 + ["dent"] * 30 + ["stain"] * 30
    noise = rng.normal(0, 1, 160)
    base = noise + 0.8 * labels  # both types seen alike
    better = base + 1.5 * (np.array(types) == "dent")  # the other model sees dents better, stains the same
    a = report(tmp_path / "a", labels, types, base)
    b = report(tmp_path / "b", labels, types, better)
    assert main(["compare", "--paired", str(a), str(b), "--resamples", "300", "--out", str(tmp_path / "p")]) == 0
    assert "paired bootstrap" in capsys.readouterr().out
    rows = {r["type"]: r for r in json.loads((tmp_path / "p" / "paired.json").read_text())["rows"]}
    assert set(rows) == {"all", "dent", "stain"} and rows["dent"]["defective"] == 30
    assert rows["dent"]["gain"] > 5 * rows["dent"]["se"] > 0  # a real gain, far beyond its paired noise
    assert rows["stain"]["gain"] == 0 and rows["stain"]["se"] == 0  # the same scores: no gain, no noise
    assert rows["all"]["base"] == rows["all"]["other"] - rows["all"]["gain"]


def test_reports_on_other_parts_or_without_scores_are_refused_in_one_line(tmp_path: Path, capsys) -> None:
    labels = np.r_[np.zeros(10), np.ones(10)].astype(int)
    types = [""] * 10 + ["dent"] * 10
    a = report(tmp_path / "a", labels, types, np.arange(20.0))
    b = report(tmp_path / "b", 1 - labels, types, np.arange(20.0))
    (tmp_path / "old").mkdir()
    for other, says in ((b, "not the same parts"), (tmp_path / "old", "no per-part scores")):
        assert main(["compare", "--paired", str(a), str(other), "--out", str(tmp_path / "p")]) == 2
        err = capsys.readouterr().err
        assert says in err and len(err.strip().splitlines()) == 1
