"""``station bench defects``: the visibility of rendered defects in each prior (a z-score against a ring)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from test_run import make_dataset  # same folder (pytest puts it on sys.path)

from station.benchmarks.defects import angle_z, normal_z, scalar_z, visibility
from station.cli import main


def test_z_scores_measure_shifts_and_symmetric_spreads_in_units_of_the_rings_spread() -> None:
    rng = np.random.default_rng(0)
    ring = rng.normal(0.0, 0.1, 10000)
    assert scalar_z(np.full(50, 0.3), ring) == pytest.approx(3.0, rel=0.05)
    assert scalar_z(ring[:500], ring) == pytest.approx(1.0, abs=0.1)  # a piece of the neighbourhood: 1
    assert scalar_z(np.repeat([-0.3, 0.3], 25), ring) == pytest.approx(3.0, rel=0.05)  # same mean, spread out
    a = rng.normal(0.0, 0.2, 10000)  # ring angles (of 2*AoLP), circular spread ~0.2 rad
    step = np.sqrt(0.6**2 + 0.2**2) / 0.2
    assert angle_z(np.cos(a[:1000] + 0.6), np.sin(a[:1000] + 0.6), np.cos(a), np.sin(a)) == pytest.approx(step, rel=0.1)
    # around the wrap at pi: the same numbers
    b = a + np.pi - 0.1
    assert angle_z(np.cos(b[:1000] + 0.6), np.sin(b[:1000] + 0.6), np.cos(b), np.sin(b)) == pytest.approx(step, rel=0.1)
    tilt = np.deg2rad(rng.normal(0.0, 5.0, (1000, 2)))
    ring_n = np.stack([np.sin(tilt[:, 0]), np.sin(tilt[:, 1]), np.ones(1000)], 1)
    ring_n /= np.linalg.norm(ring_n, axis=1, keepdims=True)
    t = np.deg2rad(20.0)
    dent = np.array([[np.sin(t), 0.0, np.cos(t)], [-np.sin(t), 0.0, np.cos(t)]] * 15)  # tilted both ways: mean 0
    assert normal_z(dent, ring_n) == pytest.approx(20.0 / 7.07, rel=0.15)  # RMS of a 2-D 5-degree spread: 7.07


def test_visibility_sees_a_step_in_one_prior_only_in_that_prior() -> None:
    rng = np.random.default_rng(1)
    maps = {"intensity": rng.normal(0.5, 0.05, (64, 64)), "dolp": rng.normal(0.2, 0.02, (64, 64))}
    a2 = rng.normal(0.0, 0.1, (64, 64))
    maps |= {"aolp_cos": np.cos(a2), "aolp_sin": np.sin(a2), "normal": np.dstack([0 * a2, 0 * a2, 1 + 0 * a2])}
    defect = np.zeros((64, 64), bool)
    defect[30:36, 30:36] = True
    maps["dolp"][defect] += 0.1
    z = visibility(maps, np.ones((64, 64), bool), defect, ring_px=4)
    assert z["dolp"] > 3 and z["pixels"] == 36
    assert 0.5 < z["intensity"] < 1.5 and 0.5 < z["aolp"] < 1.5  # unchanged priors: like the neighbourhood
    assert visibility(maps, np.zeros((64, 64), bool), defect, 4) == {}  # the defect is not on the object


def test_bench_defects_reports_per_type(tmp_path: Path) -> None:
    data = make_dataset(tmp_path / "ds", n=20)  # test split 0, 1, 10, 11; 1 and 11 carry a saturated patch
    out = tmp_path / "out"
    assert main(["bench", "defects", "--data", str(data), "--size", "32", "--out", str(out)]) == 0
    rep = json.loads((out / "defects.json").read_text())
    assert {p["index"] for p in rep["per_defect"]} == {1, 11}
    full = next(r for r in rep["rows"] if r["defect"] == "stain" and r["scale"] != "32 px")
    assert full["n"] == 2 and full["intensity_z"] > 1 and full["visible_any"] == 1.0
    assert len(rep["plots"]) == 2 and all((out / p).stat().st_size > 1000 for p in rep["plots"])
