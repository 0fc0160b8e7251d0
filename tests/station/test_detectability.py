"""Detection by detectability (station/detectability.py), station render --visibility's records and manifest
summary, and station bench visibility on tiny renders."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from sim.detectability import snr_bin, summarise
from station.cli import main
from station.detectability import detection_by_detectability


def test_bins_caught_share_and_auroc_per_bin_and_type() -> None:
    labels = [0, 0, 0, 0, 1, 1, 1, 1]
    scores = [0.1, 0.2, 0.3, 0.4, 0.05, 0.35, 0.9, 0.8]
    snr = [None, None, None, None, 0.5, 2.0, 12.0, 40.0]
    types = ["", "", "", "", "dent", "dent", "stain", "dent"]
    rows = {(r["type"], r["snr_bin"]): r for r in detection_by_detectability(labels, scores, 0.5, snr, types)}
    assert set(rows) == {("all", "<1"), ("all", "1-3"), ("all", ">10"), ("dent", "<1"), ("dent", "1-3"),
                         ("dent", ">10"), ("stain", ">10")}
    assert rows[("all", ">10")]["defects"] == 2 and rows[("all", ">10")]["caught"] == 1.0
    assert rows[("all", ">10")]["image_auroc"] == 1.0
    assert rows[("all", "<1")]["caught"] == 0.0 and rows[("all", "<1")]["image_auroc"] == 0.0  # below every good
    assert rows[("dent", "1-3")]["image_auroc"] == pytest.approx(0.75)  # 0.35 beats three of four good parts
    assert math.isnan(detection_by_detectability(labels, scores, None, snr, types)[0]["caught"])
    assert detection_by_detectability(labels, scores, 0.5, [None] * 8, types) == []  # no oracle values: no table
    assert [snr_bin(v) for v in (-1, 0.99, 1, 3, 4.9, 5, 10, 1e9)] == ["<1", "<1", "1-3", "3-5", "3-5", "5-10", ">10",
                                                                       ">10"]


def test_summary_counts_intensity_and_polarization_shares() -> None:
    def rec(typ: str, i: float, d: float, a: float, px: int = 100) -> dict:
        return {"type": typ, "snr": {"intensity": i, "dolp": d, "aolp": a, "normal": 0.0},
                "snr_demosaic": {"intensity": i, "dolp": d, "aolp": a}, "snr_oracle": {"pixels": px}}

    rows = {r["type"]: r for r in summarise([rec("dent", 2, 8, 0), rec("dent", 20, 1, 1), rec("dent", 0, 0, 0, 0),
                                             rec("stain", 30, 0, 6)])}
    assert rows["dent"]["n"] == 3 and rows["dent"]["visible"] == 2
    assert rows["dent"]["above_intensity"] == 0.5 and rows["dent"]["above_polarization"] == 0.5
    assert rows["dent"]["polarization_only"] == 0.5 and rows["dent"]["above_any"] == 1.0
    assert rows["dent"]["median_intensity"] == 11 and rows["all"]["n"] == 4
    assert rows["dent"]["median_cnr_intensity"] == pytest.approx(1.1)  # snr / sqrt(100 px)


def test_render_visibility_writes_snr_and_summary_and_bench_compares_presets(tmp_path) -> None:
    out = tmp_path / "set"
    assert main(["render", "--out", str(out), "--count", "2", "--defects", "1", "--width", "64", "--height", "48",
                 "--spp", "4", "--visibility"]) == 0
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["config"]["visibility"] is True
    assert manifest["visibility"]["by_type"][-1]["type"] == "all"
    for i in (0, 1):  # both in the test split, both given a defect
        p = json.loads((out / f"samples/{i:06d}/params.json").read_text())
        d = p["defect"]
        assert set(d["snr"]) == {"intensity", "dolp", "aolp", "normal"}
        assert d["snr_best"] in ("intensity", "dolp", "aolp")
        assert d["snr_oracle"]["spp"] == 2 and (d["snr_oracle"]["pixels"] > 0) == bool(p["label"])
        if not p["label"]:
            assert max(d["snr"].values()) == 0
    cfg = tmp_path / "a.toml"
    cfg.write_text("[scene]\ncamera_polar_deg = [20.0, 30.0]\n")
    bench = tmp_path / "bench"
    assert main(["bench", "visibility", "--config", str(cfg), "--count", "2", "--width", "64", "--height", "48",
                 "--spp", "2", "--out", str(bench)]) == 0
    report = json.loads((bench / "visibility.json").read_text())
    assert report["rows"][-1]["preset"] == "a" and (bench / "visibility.png").is_file()
    assert len((bench / "a.jsonl").read_text().splitlines()) == 2
    # resumed: nothing rendered again, same rows
    assert main(["bench", "visibility", "--config", str(cfg), "--count", "2", "--width", "64", "--height", "48",
                 "--spp", "2", "--out", str(bench)]) == 0
    assert len((bench / "a.jsonl").read_text().splitlines()) == 2
    assert np.isfinite(json.loads((bench / "visibility.json").read_text())["rows"][-1]["median_intensity"])


def test_render_benchmark_times_samples_with_and_without_the_oracle() -> None:
    from station.benchmarks.render import visibility_cost

    row = visibility_cost(4, 1, 64, 48, "sim/presets/line.toml")
    assert row["samples"] == 1 and row["visibility_s"] > row["oracle_s"] > 0
    assert row["ratio"] == pytest.approx(row["visibility_s"] / row["plain_s"])
