"""``station bench shift``: a model on held-out parts whose priors are changed as another renderer, lens or camera
would change them, with its validation thresholds fixed. The shifts are pure functions with the project's
conventions; the benchmark's unchanged row is ``station eval``'s."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from line_sets import make_line_set  # same folder (pytest puts it on sys.path)

from model.draem.shifts import SHIFTS, Channels, shift
from station.cli import main

CH = Channels(intensity=0, dolp=1, aolp=2)


def priors(n: int = 2, h: int = 16, w: int = 24, seed: int = 0) -> np.ndarray:
    """(n, 4, h, w): intensity in [0.05, 0.6], DoLP in [0, 0.5], AoLP as (cos 2a, sin 2a)."""
    rng = np.random.default_rng(seed)
    a = rng.uniform(0, np.pi, (n, h, w))
    return np.stack([rng.uniform(0.05, 0.6, (n, h, w)), rng.uniform(0.0, 0.5, (n, h, w)), np.cos(2 * a),
                     np.sin(2 * a)], 1).astype(np.float32)


def test_each_shift_changes_what_it_names_and_nothing_else() -> None:
    x = priors()
    assert np.array_equal(shift("none", x, CH), x)
    y = shift("dolp x2", x, CH)
    assert np.allclose(y[:, 1], np.minimum(2 * x[:, 1], 1.0)) and np.array_equal(y[:, [0, 2, 3]], x[:, [0, 2, 3]])
    y = shift("aolp +5 deg", x, CH)
    turned = np.angle((y[:, 2] + 1j * y[:, 3]) / (x[:, 2] + 1j * x[:, 3]))  # 2 * AoLP turns by 10 degrees
    assert np.allclose(turned, math.radians(10), atol=1e-5) and np.array_equal(y[:, :2], x[:, :2])
    y = shift("gamma 1.25", x, CH)
    assert np.allclose(y[:, 0], x[:, 0] ** 1.25) and np.array_equal(y[:, 1:], x[:, 1:])
    # exposure below full scale: intensity scales, DoLP and AoLP stay
    y = shift("exposure x1.3", x * np.array([0.5, 1, 1, 1], np.float32)[None, :, None, None], CH)
    assert np.allclose(y[:, 0], 1.3 * 0.5 * x[:, 0], rtol=1e-5) and np.allclose(y[:, 1], x[:, 1], atol=1e-5)
    # a uniform frame stays uniform under blur; a polarization edge blurs in the Stokes vector
    flat = np.ones_like(x) * np.array([0.4, 0.3, 1.0, 0.0], np.float32)[None, :, None, None]
    assert np.allclose(shift("blur 1 px", flat, CH), flat, atol=1e-6)


def test_geometric_shifts_move_the_part_and_turn_its_polarization_with_it() -> None:
    x = np.zeros((1, 4, 21, 21), np.float32)
    x[:, 0], x[:, 1], x[:, 2] = 0.1, 0.2, 1.0  # AoLP 0 everywhere
    x[0, 0, 10, 14] = 0.9  # a bright dot 4 px right of the centre
    at = lambda y: np.unravel_index(np.argmax(y[0, 0]), y.shape[2:])  # noqa: E731
    assert at(shift("move 2 px", x, CH)) == (10, 16)
    y = shift("rotate 90 deg", x, CH)
    assert at(y) == (6, 10)  # counter-clockwise as displayed: right of the centre goes up (row 0 is the top)
    aolp = 0.5 * np.degrees(np.arctan2(y[0, 3], y[0, 2]))
    assert np.allclose(np.abs(aolp), 90, atol=1e-3) and np.allclose(y[0, 1], 0.2, atol=1e-5)  # AoLP turns with it
    assert at(shift("zoom x1.5", x, CH)) == (10, 16)  # 4 px out becomes 6
    y = shift("rotate 5 deg", x, CH)
    assert np.allclose(0.5 * np.degrees(np.arctan2(y[0, 3, 0, 0], y[0, 2, 0, 0])), 5, atol=1e-3)


def test_shifts_joined_by_an_ampersand_apply_in_order() -> None:
    """Another renderer changes several things at once: "dolp x0.5 & blur 1 px" is the one shift after the other."""
    x = priors()
    both = shift("dolp x0.5 & blur 1 px", x, CH)
    assert np.allclose(both, shift("blur 1 px", shift("dolp x0.5", x, CH), CH), atol=1e-6)  # OpenCV: 1e-7 apart
    assert not np.allclose(both, shift("blur 1 px", x, CH)) and not np.allclose(both, shift("dolp x0.5", x, CH))
    with pytest.raises(ValueError, match=re.escape("unknown shift 'dolp x0.5 & sharpen 1'")):
        shift("dolp x0.5 & sharpen 1", x, CH)


def test_exposure_clips_each_polarizer_reading_and_polarization_falls_where_they_clip() -> None:
    x = priors() * np.array([0, 0, 1, 1], np.float32)[None, :, None, None]
    x[:, 0], x[:, 1] = 0.9, 0.5  # brightest reading 0.9 * 1.5 = 1.35: clips at full scale
    y = shift("exposure x1.3", x, CH)
    assert (y[:, 0] < 1.3 * 0.9).all() and (y[:, 1] < 0.5).all() and (y[:, 0] <= 1.0).all()


def test_hostile_priors_stay_finite_under_every_shift() -> None:
    x = priors()
    x[0, 0, 0, 0], x[0, 1, 0, 1], x[1, 2, 3, 3], x[1, 0, 2, 2] = np.nan, np.inf, -np.inf, 0.0
    x[1, 0] = 0.0  # a black frame
    for name in SHIFTS:
        assert np.isfinite(shift(name, x, CH)).all(), name
    for bad in ("sharpen 2", "dolp", "dolp xabc", "blur -1 px", "gamma nan", "zoom x0", "zoom x-1"):
        with pytest.raises(ValueError, match="unknown shift"):
            shift(bad, x, CH)


def test_bench_shift_reports_every_shift_and_its_unchanged_row_is_station_evals(tmp_path: Path, capsys) -> None:
    data = make_line_set(tmp_path / "ds", n=60, defective=lambda i: i % 3 == 1)
    held = make_line_set(tmp_path / "held", n=24, seed=5, defective=lambda i: i % 2 == 1, heldout=True)
    base = ["--priors", "intensity,dolp,aolp", "--preset", "tiny", "--size", "32", "--steps", "2", "--batch-size", "4",
            "--eval-every", "2", "--device", "cpu", "--roi", "band"]
    assert main(["train", "--data", str(data), *base, "--out", str(tmp_path / "t")]) == 0
    assert main(["variation", "--model", str(tmp_path / "t" / "last"), "--data", str(data),
                 "--out", str(tmp_path / "v")]) == 0
    out = tmp_path / "bench"
    assert main(["bench", "shift", "--model", str(tmp_path / "v"), "--data", str(held), "--val-data", str(data),
                 "--shifts", "none,dolp x2,blur 1 px", "--out", str(out)]) == 0
    report = json.loads((out / "shift.json").read_text())
    assert [r["shift"] for r in report["rows"]] == ["none", "dolp x2", "blur 1 px"] and report["parts"] == 24
    assert all(math.isfinite(r[k]) for r in report["rows"] for k in ("image_auroc", "caught_1%", "good_rejected_1%"))
    assert (out / "shift.md").exists() and (out / "shift.png").exists()
    capsys.readouterr()
    assert main(["eval", "--model", str(tmp_path / "v"), "--data", str(held), "--no-plots", "--no-synthetic",
                 "--out", str(tmp_path / "ev")]) == 0
    rendered = json.loads((tmp_path / "ev" / "eval.json").read_text())["rows"][0]  # all defects of the set
    assert report["rows"][0]["image_auroc"] == pytest.approx(rendered["image_auroc"], abs=1e-9)
    # an unknown shift is refused in one line, before anything is loaded
    capsys.readouterr()
    assert main(["bench", "shift", "--model", str(tmp_path / "v"), "--data", str(held), "--val-data", str(data),
                 "--shifts", "dolp xabc", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "unknown shift 'dolp xabc'" in err and len(err.strip().splitlines()) == 1
