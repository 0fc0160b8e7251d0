"""The variation model's second look (``model.draem.second_look``): regions around the map's highest places, tested
against the good parts' references; only parts above the window's 5 % gate are looked at again, and the part at the
gate is not; it survives a checkpoint, an old file loads without it, and no input makes it NaN."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import torch

from model.draem.checkpoint import load_checkpoint, save_checkpoint
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.draem.errors import CheckpointError
from model.draem.metrics import false_reject_threshold
from model.draem.second_look import MAX_PX, SecondLook, proposals, robust_location_spread
from model.draem.with_variation import add_variation
from tests.model.test_variation import parts


def blob(cy: float, cx: float, height: float, r: float = 2.0, shape: tuple[int, int] = (40, 80)) -> np.ndarray:
    y, x = np.mgrid[0:shape[0], 0:shape[1]].astype(np.float32)
    return height * np.exp(-((y - cy) ** 2 + (x - cx) ** 2) / (2 * r * r))


def test_proposals_are_the_regions_around_the_highest_places_highest_first() -> None:
    m = blob(10, 10, 5.0) + blob(30, 60, 8.0)
    regs = proposals(m)
    assert regs[0][30, 60] and not regs[0][10, 10]
    assert regs[1][10, 10] and not regs[1][30, 60]
    assert proposals(np.zeros((40, 80), np.float32)) == []
    wide = proposals(blob(20, 40, 1.0, r=30.0))[0]  # a plateau larger than MAX_PX: the pixels nearest the peak
    assert wide[20, 40] and MAX_PX <= wide.sum() <= MAX_PX + 120  # grown by 1 px after the cut


def references(n: int, seed: int, shape: tuple[int, int] = (40, 80)) -> np.ndarray:
    """(n, 3, H, W) signed residuals of good parts: unit normal per channel, zero on the first column (not judged)."""
    s = np.random.default_rng(seed).standard_normal((n, 3, *shape)).astype(np.float32)
    s[..., 0] = 0.0
    return s


def test_a_region_whose_residual_runs_higher_than_the_references_there_tests_high() -> None:
    region = np.ones((40, 80), bool)
    look = SecondLook()
    look.fit(references(60, 0), region)
    assert look.references == 60 and look.chi.dtype == torch.float16
    own = references(1, 1)[0]
    judged = np.ones((40, 80), bool)
    m = blob(20, 40, 3.0)
    plain = look.test(m, (own ** 2).sum(0), judged, region)
    own[:, 17:24, 37:44] *= 2.0  # the proposed region's residual twice the good parts' spread: chi-square x4
    raised = look.test(m, (own ** 2).sum(0), judged, region)
    assert plain < 2.0 < raised
    chi = (own ** 2).sum(0)
    chi[20, 40] = np.nan
    chi[21, 41] = np.inf
    assert np.isfinite(look.test(m, chi, judged, region))
    assert look.test(np.zeros((40, 80), np.float32), chi, judged, region) == 0.0  # nothing proposed


def test_a_regions_test_counts_only_the_references_judged_pixels() -> None:
    """The references' judged pixels are kept as bits; a region over the unjudged first column must average each
    reference's chi-square over its judged pixels only (the oracle's statistic), computed here by hand."""
    region = np.ones((40, 80), bool)
    refs = references(40, 4)
    look = SecondLook()
    look.fit(refs, region)
    m = blob(20, 1, 3.0)
    reg = proposals(m)[0]
    assert reg[:, 0].any() and reg[:, 1:].any()  # the region straddles the unjudged column
    own = references(1, 5)[0]
    judged = np.ones((40, 80), bool)
    chi = (own ** 2).sum(0)
    ref_chi = (refs ** 2).sum(1).astype(np.float16).astype(np.float32)[:, reg]
    ref_judged = (refs != 0).any(1)[:, reg]
    r = ref_chi.sum(1) / ref_judged.sum(1)
    med, q = np.median(r), np.percentile(r, 95.0)
    want = max(0.0, (chi[reg].mean() - med) / (q - med))
    for extra in proposals(m)[1:]:  # the other places, scored the same way
        rc = (refs ** 2).sum(1).astype(np.float16).astype(np.float32)[:, extra]
        re = rc.sum(1) / (refs != 0).any(1)[:, extra].sum(1)
        mm, qq = np.median(re), np.percentile(re, 95.0)
        want = max(want, (chi[extra].mean() - mm) / (qq - mm))
    assert look.test(m, chi, judged, region) == pytest.approx(want, rel=1e-5)


def test_only_parts_above_the_gate_are_looked_at_again_and_the_part_at_the_gate_is_not() -> None:
    """The 5 % threshold is the (k+1)-th largest good score (``false_reject_threshold``): that part itself. Rule 46
    gated with >= and its second look raised that part and the threshold with it (caught at 5 % -1.3 points)."""
    look = SecondLook()
    look.fit(references(30, 0), np.ones((40, 80), bool))
    window = np.random.default_rng(2).gamma(2.0, 1.0, 200)
    test = np.random.default_rng(3).gamma(2.0, 1.0, 200)
    look.calibrate(window, test)
    at_gate = false_reject_threshold(window, 0.05)
    assert not look.suspicious(float(at_gate))
    assert look.suspicious(float(np.sort(window)[-1]))
    wl, ws = robust_location_spread(window)
    tl, ts = robust_location_spread(test)
    top = float(np.sort(window)[-1])
    assert look.score(top, 0.0) == top  # the look can only raise a part
    assert look.score(top, 1e3) == pytest.approx(wl + ws * (1e3 - tl) / ts)
    assert not SecondLook().suspicious(1e9)  # without references, never


def with_second_look(tmp_path: Path) -> tuple[Detector, Detector, Path]:
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "fused", 32, "band"))
    det.init_weights(torch.Generator().manual_seed(0))
    det.eval()
    plain = add_variation(det, parts(40, 0), None, parts(30, 3))
    looked = add_variation(det, parts(40, 0), None, parts(30, 3), second_look=True)
    path = tmp_path / "look"
    save_checkpoint(path, looked, threshold=0.5, threshold_rule="test")
    return plain, looked, path


def test_the_second_look_only_raises_parts_above_its_gate_and_survives_a_checkpoint(tmp_path: Path) -> None:
    plain, looked, path = with_second_look(tmp_path)
    assert plain.variation is not None and looked.variation is not None
    look = looked.variation.second_look
    assert look.references == 40 and look.chi.shape[1] == int(looked.variation.region.sum())
    x = torch.cat([parts(30, 4), parts(10, 5, defect=True)])
    before, after = plain.variation.zmaps(x).scores, looked.variation.zmaps(x).scores
    gated = np.array([look.suspicious(float(s)) for s in before])
    assert gated[30:].all() and not gated[:30].all()  # the defects and at most a few good parts
    assert torch.equal(after[~torch.from_numpy(gated)], before[~torch.from_numpy(gated)])
    assert bool((after >= before).all()) and bool((after > before).any())  # it looked, and it raised some
    loaded = load_checkpoint(path).detector
    assert loaded.variation is not None and loaded.variation.second_look.references == 40
    assert torch.equal(loaded.variation.zmaps(x).scores, after)
    nasty = parts(2, 6)
    nasty[0], nasty[1] = float("nan"), float("inf")
    assert bool(torch.isfinite(loaded.variation.zmaps(nasty).scores).all())


def test_a_file_whose_references_do_not_cover_the_part_region_is_refused(tmp_path: Path) -> None:
    _, _, path = with_second_look(tmp_path)
    pt = path.with_suffix(".pt")
    state = torch.load(pt, weights_only=True)
    state["variation.second_look.chi"] = state["variation.second_look.chi"][:, :-8]
    torch.save(state, pt)
    with pytest.raises(CheckpointError, match=r"second_look\.chi has shape"):
        load_checkpoint(path, verify_hash=False)


def test_a_file_without_a_second_look_scores_as_before(tmp_path: Path) -> None:
    plain, _, path = with_second_look(tmp_path)
    pt = path.with_suffix(".pt")
    save_checkpoint(path, plain, threshold=0.5, threshold_rule="test")
    state = torch.load(pt, weights_only=True)
    for key in [k for k in state if k.startswith("variation.second_look.")]:
        del state[key]
    torch.save(state, pt)
    loaded = load_checkpoint(path, verify_hash=False).detector
    assert loaded.variation is not None and loaded.variation.second_look.references == 0
    x = parts(5, 7, defect=True)
    assert plain.variation is not None
    assert torch.equal(loaded.variation.zmaps(x).scores, plain.variation.zmaps(x).scores)


def test_adapting_fits_the_second_look_on_the_lines_parts_or_drops_it_when_too_few(tmp_path: Path) -> None:
    from model.draem.adapt import AdaptConfig, adapt

    _, looked, _ = with_second_look(tmp_path)
    line = parts(40, 8)
    adapted, result = adapt(looked, line, torch.ones(len(line), *line.shape[2:], dtype=torch.bool),
                            AdaptConfig(false_reject=0.05), progress=False)
    look = adapted.variation.second_look
    assert look.references == 40 and bool(torch.isfinite(look.calibration).all())
    assert np.isfinite(result.heldout_scores).all()
    few = parts(15, 9)  # each fold's fit has 12 parts, under MIN_REFERENCES
    adapted, _ = adapt(looked, few, torch.ones(len(few), *few.shape[2:], dtype=torch.bool), progress=False)
    assert adapted.variation.second_look.references == 0


def test_a_gate_only_second_look_keeps_every_window_score_survives_a_checkpoint_and_a_refit(tmp_path: Path) -> None:
    """``second_look_test=False`` (step 4): the second look only gates the parts a look network is asked about, so
    every part keeps its window score, above the gate too; the file and a refit (``station adapt``) keep it, and a
    file from before it tests, as it did."""
    plain, looked, path = with_second_look(tmp_path)
    det = Detector(ModelConfig.from_preset("tiny", ("intensity", "dolp", "aolp"), "fused", 32, "band"))
    det.init_weights(torch.Generator().manual_seed(0))
    det.eval()
    gated = add_variation(det, parts(40, 0), None, parts(30, 3), second_look=True, second_look_test=False)
    assert gated.variation is not None and plain.variation is not None and looked.variation is not None
    look = gated.variation.second_look
    assert look.references == 40 and not look.testing and looked.variation.second_look.testing
    x = torch.cat([parts(30, 4), parts(10, 5, defect=True)])
    window = plain.variation.zmaps(x).scores
    assert sum(look.suspicious(float(s)) for s in window) >= 10  # the gate is there: the defects are above it
    assert torch.equal(gated.variation.zmaps(x).scores, window)
    assert not torch.equal(looked.variation.zmaps(x).scores, window)  # the testing look raised some
    save_checkpoint(tmp_path / "gate", gated, threshold=0.5, threshold_rule="test")
    loaded = load_checkpoint(tmp_path / "gate").detector.variation
    assert loaded is not None and not loaded.second_look.testing
    loaded.fit(parts(30, 8), keep_reference=True)
    assert not loaded.second_look.testing
    state = torch.load(path.with_suffix(".pt"), weights_only=True)
    del state["variation.second_look.tests"]
    torch.save(state, path.with_suffix(".pt"))
    old = load_checkpoint(path, verify_hash=False).detector.variation
    assert old is not None and old.second_look.testing
