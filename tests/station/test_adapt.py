"""``station adapt``: a model trained on one line, shown a brighter (other exposure, 12-bit) line, rejects its good
parts; adapted on good parts of that line it rejects far fewer, and its sidecar says what it was adapted on."""

from __future__ import annotations

import json
import logging
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
import torch
from line_sets import make_line_set  # same folder (pytest puts it on sys.path)

from model.draem.adapt import AdaptConfig, adapt, adapted_threshold
from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.config import ModelConfig
from model.draem.errors import ModelError
from model.draem.roi import AROUND_PX
from model.draem.train import TensorData, TrainConfig, train
from station.cli import main
from station.datasets import load_split
from station.evaluation import load_and_evaluate

PRIORS = ("intensity", "aolp")


@pytest.fixture(scope="module")
def line(tmp_path_factory) -> Iterator[tuple[Path, Path, Path]]:
    """(trained model, its training set, a shifted set: 1.6x exposure, 12-bit sensor). A tiny DRAEM trained 60
    steps (a few seconds) already scores the brighter frames above every good part of its own line."""
    threads = torch.get_num_threads()
    torch.set_num_threads(1)  # the same training steps, hence the same model, whatever the machine
    tmp = tmp_path_factory.mktemp("adapt")
    base = make_line_set(tmp / "base", 30, seed=0)
    shifted = make_line_set(tmp / "shifted", 200, gain=1.6, bit_depth=12, seed=10)
    tr = load_split(base, "train", PRIORS, 32, good_only=True, progress=False)
    cfg = ModelConfig.from_preset("tiny", PRIORS, "fused", 32)
    train(cfg, TensorData(tr.priors, tr.object_mask), tmp / "m", TrainConfig(steps=60, batch_size=4, eval_every=60,
                                                                            device="cpu"), progress=False)
    assert main(["threshold", "--model", str(tmp / "m" / "last"), "--data", str(base)]) == 0
    yield tmp / "m" / "last", base, shifted
    torch.set_num_threads(threads)


def _false_rejects(model: Path, data: Path) -> float:
    ck, _, sp, _, ev = load_and_evaluate(str(model), data, "test")
    good = sp.label.numpy() == 0
    return float((ev.scores[good] >= ck.threshold).mean())


def test_adapt_lowers_false_rejects_on_a_shifted_line(line, tmp_path: Path, capsys) -> None:
    model, _, shifted = line
    before = _false_rejects(model, shifted)
    assert before > 0.5  # the line's exposure changed: most good parts rejected
    out = tmp_path / "adapted"
    assert main(["adapt", "--model", str(model), "--good", str(shifted), "--out", str(out),
                 "--false-reject", "0.05"]) == 0
    out_text = capsys.readouterr().out
    assert "adapted on 140 good parts" in out_text and "recommended" not in out_text  # no variation model: no note
    held = json.loads(out.with_suffix(".json").read_text())["train"]["adapted"]
    k = held["n_heldout_rejected"]  # the count itself, kept beside the share
    assert k == round(held["heldout_false_reject"] * held["n_heldout"])
    assert f"({k} of {held['n_heldout']}; new good parts: about " in out_text  # what the count can promise
    after = _false_rejects(out, shifted)  # test split: parts the adaptation never saw
    assert after < before and after <= 0.2
    side = json.loads(out.with_suffix(".json").read_text())
    rec = side["train"]["adapted"]
    assert rec["n_good"] == 140 and len(rec["frames_sha256"]) == 64 and len(rec["manifest_sha256"]) == 64
    assert rec["date"][:2] == "20" and rec["base_model"] == str(model) and rec["false_reject_target"] == 0.05
    assert side["threshold"] == pytest.approx(rec["threshold"])
    assert side["train"]["frame_statistics"]["n_frames"] == 140
    base_mean = load_checkpoint(model).detector.normalizer.mean[0]
    assert side["normalization"]["mean"][0] > 1.3 * base_mean  # intensity normalisation refitted (brighter)


def test_adapt_refuses_too_few_parts_and_writing_over_its_model(line, tmp_path: Path, capsys) -> None:
    model, _, shifted = line
    assert main(["adapt", "--model", str(model), "--good", str(shifted), "--out", str(tmp_path / "a"),
                 "--limit", "5"]) == 2
    assert "at least 10 good parts" in capsys.readouterr().err
    assert main(["adapt", "--model", str(model), "--good", str(shifted), "--out", str(model)]) == 2
    assert "same checkpoint" in capsys.readouterr().err


def test_adapted_threshold_extrapolates_beyond_the_largest_of_few_scores() -> None:
    rng = np.random.default_rng(0)
    s = 1 / (1 + np.exp(-rng.normal(-1.0, 0.3, 50)))
    t = adapted_threshold(s, 0.01)
    assert t.threshold >= s.max() and "50 held-out" in t.rule
    many = 1 / (1 + np.exp(-rng.normal(-1.0, 0.3, 100_000)))
    assert 0.003 < float((many >= t.threshold).mean()) < 0.03  # about the 1 % asked for on the population
    t20 = adapted_threshold(s, 0.2)
    assert float((s >= t20.threshold).mean()) <= 0.2


def test_fine_tune_keeps_parts_out_for_the_threshold(line) -> None:
    model, _, shifted = line
    ck = load_checkpoint(model)
    sp = load_split(shifted, "train", PRIORS, 32, good_only=True, progress=False)
    det, res = adapt(ck.detector, sp.priors, sp.object_mask, AdaptConfig(fine_tune_steps=3, batch_size=2))
    assert res.n_heldout == round(0.3 * 140) and res.fine_tune_steps == 3 and "fine-tune" in res.scheme
    changed = any(not torch.equal(a, b) for a, b in zip(det.state_dict().values(), ck.detector.state_dict().values(),
                                                         strict=True))
    assert changed
    with pytest.raises(ModelError, match="false_reject"):
        AdaptConfig(false_reject=0.0)


def test_adapt_refits_the_variation_models_statistics_and_calibration(line, tmp_path: Path, capsys) -> None:
    """The variation model's per-pixel statistics depend on the line: adapt re-estimates them (reference and part
    region kept) and sets the calibration from cross-fitted held-out scores. (Its log-intensity features do not
    move with exposure, so unlike the networks alone it does not reject this brighter line before adapting.)"""
    model, base, shifted = line
    with_var = tmp_path / "var"
    assert main(["variation", "--model", str(model), "--data", str(base), "--out", str(with_var)]) == 0
    out = tmp_path / "adapted"
    assert main(["adapt", "--model", str(with_var), "--good", str(shifted), "--out", str(out),
                 "--false-reject", "0.05"]) == 0
    assert "note: 140 good parts, fewer than the 200 recommended" in capsys.readouterr().out
    assert _false_rejects(out, shifted) <= 0.2
    old, new = load_checkpoint(with_var).detector.variation, load_checkpoint(out).detector.variation
    assert old is not None and new is not None
    assert torch.equal(old.reference, new.reference) and torch.equal(old.region, new.region)
    assert not torch.equal(old.mean, new.mean) and not torch.equal(old.calibration, new.calibration)
    # the fit reads the frame around its view at a station, and so do the refit, its held-out scores and the adapted
    # file (this line's parts lie 8-18 % outside the view: a refit on the view alone, read with the frame around,
    # scored every good part above the threshold; the false rejects above are read with it)
    assert load_checkpoint(with_var).detector.config.around_px == AROUND_PX
    assert load_checkpoint(out).detector.config.around_px == AROUND_PX
    x = torch.zeros(12, len(PRIORS), 32, 32)
    with pytest.raises(ModelError, match="the model reads 16 input px around each of 12 views"):
        adapt(load_checkpoint(with_var).detector, x, x[:, 0] > 0, around=x)
    # the second look is fitted again too: the line's own parts as references, its gate from their held-out scores
    assert old.second_look.references > 0 and new.second_look.references == 140
    assert bool(torch.isfinite(new.second_look.calibration).all())
    assert not torch.equal(old.second_look.calibration, new.second_look.calibration)
    rec = json.loads(out.with_suffix(".json").read_text())["train"]["adapted"]
    assert "variation" in rec["per_position"] and "variation statistics" in rec["scheme"]
    assert rec["advice"].startswith("140 good parts, fewer than the 200 recommended")


def test_networks_out_of_their_domain_leave_the_decision_to_the_variation_model(line, tmp_path: Path, capsys,
                                                                                 monkeypatch) -> None:
    """Networks whose good parts score far above their validation parts on a line are out of their domain: the
    adapted model decides on the (refitted) variation model alone, says so, and records it; --keep-networks keeps
    them. The limit is moved here to take both branches on one line; 60 parts keep every fold's fit above the
    second look's minimum and cost under half of the split's 140."""
    from model.draem.variation import squash
    from model.draem.with_variation import member_scores

    LIMIT = ("--limit", "60")

    model, base, shifted = line
    with_var = tmp_path / "var"
    assert main(["variation", "--model", str(model), "--data", str(base), "--decision", "combined",
                 "--out", str(with_var)]) == 0
    monkeypatch.setattr("model.draem.adapt.DOMAIN_SHIFT_SD", -1e9)  # every line is out of the networks' domain
    out, kept = tmp_path / "variation-only", tmp_path / "kept"
    assert main(["adapt", "--model", str(with_var), "--good", str(shifted), *LIMIT, "--out", str(out)]) == 0
    assert "decides on the variation model alone" in capsys.readouterr().out
    assert main(["adapt", "--model", str(with_var), "--good", str(shifted), *LIMIT, "--out", str(kept),
                 "--keep-networks"]) == 0
    ck = load_checkpoint(out)
    assert ck.detector.config.decision == "variation" and load_checkpoint(kept).detector.config.decision == "combined"
    rec = json.loads(out.with_suffix(".json").read_text())["train"]["adapted"]
    assert rec["decision"] == "variation" and rec["decision_changed"] and isinstance(rec["networks_shift_sd"], float)
    sp = load_split(shifted, "test", PRIORS, 32, progress=False)
    _, var = member_scores(ck.detector, sp.priors)
    vl, vs = (float(c) for c in ck.detector.variation.calibration[2:])
    assert torch.allclose(ck.detector.predict(sp.priors).score, squash((var - vl) / vs), atol=1e-6)
    monkeypatch.setattr("model.draem.adapt.DOMAIN_SHIFT_SD", 1e9)
    assert main(["adapt", "--model", str(with_var), "--good", str(shifted), *LIMIT,
                 "--out", str(tmp_path / "in")]) == 0
    assert load_checkpoint(tmp_path / "in").detector.config.decision == "combined"
    # a model that already decides on the variation model alone keeps that, and does not blame the networks
    alone = tmp_path / "alone"
    assert main(["variation", "--model", str(model), "--data", str(base), "--decision", "variation",
                 "--out", str(alone)]) == 0
    capsys.readouterr()
    assert main(["adapt", "--model", str(alone), "--good", str(shifted), *LIMIT,
                 "--out", str(tmp_path / "alone-in")]) == 0
    said = capsys.readouterr().out
    assert "as the model did" in said and "out of their domain" not in said
    rec = json.loads((tmp_path / "alone-in").with_suffix(".json").read_text())["train"]["adapted"]
    assert rec["decision"] == "variation" and rec["decision_changed"] is False


def test_adapt_leaves_out_frames_the_station_would_not_judge(line, tmp_path: Path, capsys) -> None:
    """Black frames (no part in view) among a line's good parts used to count as good parts: their held-out
    scores set the threshold, and defective parts passed."""
    model, _, _ = line
    from sim.dataset import open_dataset

    good = make_line_set(tmp_path / "good", 80, gain=1.6, bit_depth=12, seed=20, defective=lambda i: False,
                         blank=lambda i: i < 12)
    train = open_dataset(good).indices("train")
    blank = [i for i in train if i < 12]
    assert len(blank) >= 3
    out = tmp_path / "adapted"
    assert main(["adapt", "--model", str(model), "--good", str(good), "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert f"left out {len(blank)} frames the station would not judge: sample {blank[0]}: no part in view" in text
    record = load_checkpoint(out).meta["train"]["adapted"]
    assert record["left_out"] == {str(i): "no part in view" for i in blank}
    assert record["n_good"] == len(train) - len(blank)


def test_adapt_refits_the_shape_check_on_the_lines_parts_or_says_why_it_cannot(line, tmp_path: Path, capsys,
                                                                               caplog) -> None:
    """The shape check's spread and threshold were the renders' (``station shape``); adapting used to drop the check
    (with a warning), so an adapted station let bent parts through. It is refitted on the line's good parts, cross-
    fitted as the threshold is; with too few of them it is off, and the log and the summary say why."""
    model, base, shifted = line
    with_var, shaped, out, few = (tmp_path / n for n in ("var", "shaped", "adapted", "few"))
    assert main(["variation", "--model", str(model), "--data", str(base), "--out", str(with_var)]) == 0
    assert main(["shape", "--model", str(with_var), "--data", str(base), "--val-data", str(shifted),
                 "--out", str(shaped)]) == 0
    capsys.readouterr()
    assert main(["adapt", "--model", str(shaped), "--good", str(shifted), "--out", str(out), "--no-floor-checks",
                 "--false-reject", "0.05"]) == 0
    said = capsys.readouterr().out
    assert "shape check refitted: the bottom edge over input columns" in said
    # these 32 px parts are too small for the outline check's runs: station shape fitted none, and adapt adds none
    assert "outline" not in said and not load_checkpoint(out).detector.variation.outline.fitted
    before, after = (load_checkpoint(p).detector.variation.shape for p in (shaped, out))
    assert after.fitted and torch.equal(after.edge, before.edge)  # the reference is kept: the same edge
    assert not torch.equal(after.calibration, before.calibration)  # the line's parts' spread and threshold
    assert json.loads(out.with_suffix(".json").read_text())["train"]["adapted"]["shape"].startswith(
        "shape check refitted")
    # by default (--floor-checks) the refitted threshold is no lower than the model's own (here raised above the
    # refit's): on 90 parts of seed 1203 the refit alone rejected 9 of 206 good parts, floored 2
    refit = float(after.calibration[2])
    ck = load_checkpoint(shaped)
    ck.detector.variation.shape.calibration[2] = refit + 2.0
    high, floored = tmp_path / "high", tmp_path / "floored"
    save_checkpoint(high, ck.detector, ck.threshold, "test", None, {}, ck.meta.get("train"))
    assert main(["adapt", "--model", str(high), "--good", str(shifted), "--out", str(floored),
                 "--false-reject", "0.05"]) == 0
    said = capsys.readouterr().out
    assert f"threshold z {refit + 2.0:.2f} (the trained model's; the largest held-out part's {refit:.2f})" in said
    assert float(load_checkpoint(floored).detector.variation.shape.calibration[2]) == refit + 2.0
    with caplog.at_level(logging.WARNING):
        assert main(["adapt", "--model", str(shaped), "--good", str(shifted), "--out", str(few), "--limit", "12",
                     "--false-reject", "0.05"]) == 0
    assert "no shape check: shape check: the edge is seen on" in caplog.text
    assert "no shape check" in capsys.readouterr().out
    assert not load_checkpoint(few).detector.variation.shape.fitted
