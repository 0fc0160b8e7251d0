"""Numerical stress of the whole per-part pipeline (mosaic -> priors -> DRAEM checkpoint -> score): hostile frames
never give NaN/Inf, scores stay in [0, 1], and bf16 and int8 decide like fp32 within stated bounds."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from test_run import make_model  # same folder (pytest puts it on sys.path)

from drivers.frame import Frame
from model.priors import IMX250MZR
from model.priors.mosaic import stokes_to_mosaic
from model.priors.testing import detailed_stokes
from station.inspector import Inspector
from station.model_detector import DraemDetector

H, W = 48, 64
SHIPPED = Path(__file__).parents[2] / "model" / "weights" / "default"
BF16_SCORE_BOUND = 0.02
"""Largest |score(bf16) - score(fp32)| accepted for trained networks on the hostile frames below (measured 0.0033
with scores spread over 0.42..0.52, 2026-11-24; the previous model's 0.0009 over 0.10..0.38)."""


@pytest.fixture(scope="module")
def model_path(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return make_model(tmp_path_factory.mktemp("stress") / "best")


@pytest.fixture(scope="module")
def inspectors(model_path: Path) -> dict[str, Inspector]:
    detector = DraemDetector(model_path, "cpu")
    return {m: Inspector(detector, IMX250MZR, m, display_priors=("dolp", "aolp"))
            for m in ("bilinear", "superpixel", "residual")}


def hostile_frame(kind: str, bits: int, seed: int) -> np.ndarray:
    """A raw mosaic of one hostile kind at ``bits`` significant bits (uint8 for 8, else uint16)."""
    rng = np.random.default_rng(seed)
    top = 2**bits - 1
    dtype = np.uint8 if bits == 8 else np.uint16
    if kind == "dark":
        return np.zeros((H, W), dtype)
    if kind == "saturated":
        return np.full((H, W), top, dtype)
    if kind == "constant":
        return np.full((H, W), rng.integers(0, top + 1), dtype)
    if kind == "noise":  # every pixel independent: DoLP anywhere in [0, 1], AoLP random
        return rng.integers(0, top + 1, (H, W)).astype(dtype)
    if kind == "one_hot":  # one polarizer channel lit: DoLP = 1 exactly
        raw = np.zeros((H, W), dtype)
        raw[1::2, 1::2] = top
        return raw
    s0, s1, s2 = detailed_stokes(H, W, seed=seed)  # a real scene, half of it clipped
    return np.clip(stokes_to_mosaic(s0, s1, s2) * top * 1.5, 0, top).astype(dtype)


KINDS = ("dark", "saturated", "constant", "noise", "one_hot", "scene")


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(kind=st.sampled_from(KINDS), bits=st.sampled_from((8, 10, 12, 16)), seed=st.integers(0, 2**16),
       method=st.sampled_from(("bilinear", "superpixel", "residual")))
def test_hostile_frames_give_finite_scores_in_range(inspectors: dict[str, Inspector], kind: str, bits: int,
                                                    seed: int, method: str) -> None:
    inspector = inspectors[method]
    raw = hostile_frame(kind, bits, seed)
    frame = Frame(raw, "Mono8" if bits == 8 else "Mono16", bits, 1, 0, time.time_ns())
    result = inspector.inspect(frame)
    assert result.error is None, result.error
    assert 0.0 <= result.score <= 1.0
    assert np.isfinite(result.heatmap).all() and result.heatmap.min() >= 0 and result.heatmap.max() <= 1
    for name, prior in result.priors.items():
        assert np.isfinite(prior).all(), name
    assert 0.0 <= result.priors["dolp"].min() and result.priors["dolp"].max() <= 1.0


TRAINED_NETWORKS = "9cf5dec"
"""A commit whose shipped file (E63, 2026-12-02 to 2026-12-04) had trained DRAEM networks. The shipped file since
reads intensity alone and its networks, which do not decide, are a 30-step shell whose scores barely move with the
input (0.472..0.487 on the frames below), so bf16 is measured on these."""


def trained_networks(tmp: Path) -> Path:
    """E63's networks without its variation member (which is numpy fp32 whatever the precision and puts every hostile
    frame near 1) and the residual network that reads it, saved as a checkpoint: what bf16 changes. Read from git
    history (a clone without that commit skips, saying so)."""
    import subprocess

    from model.draem.checkpoint import load_checkpoint, save_checkpoint
    from model.draem.detector import Detector

    root = Path(__file__).parents[2]
    for ext in ("pt", "json"):
        done = subprocess.run(["git", "-C", str(root), "show", f"{TRAINED_NETWORKS}:model/weights/default.{ext}"],
                              capture_output=True)
        if done.returncode:
            pytest.skip(f"git history without {TRAINED_NETWORKS} (a shallow clone): no trained networks to measure")
        (tmp / f"default.{ext}").write_bytes(done.stdout)
    ck = load_checkpoint(tmp / "default")
    nets = Detector(ck.detector.config.with_(variation=False, decision="combined", residual_members=0),
                    ck.detector.normalizer)
    nets.load_state_dict({k: v for k, v in ck.detector.state_dict().items()
                          if not k.startswith(("variation.", "residual."))})
    save_checkpoint(tmp / "networks", nets, threshold=0.5, threshold_rule="test")
    return tmp / "networks"


def test_bf16_decides_like_fp32_within_the_bound(tmp_path: Path) -> None:
    """On trained networks (E63's): a random-weight model's scores do not depend on the input at all, nor do the
    shipped shell's much."""
    nets = trained_networks(tmp_path)
    fp32 = Inspector(DraemDetector(nets, "cpu", "fp32"), IMX250MZR)
    bf16 = Inspector(DraemDetector(nets, "cpu", "bf16"), IMX250MZR)
    scores, diffs = [], []
    for seed, kind in enumerate(KINDS):
        frame = Frame(hostile_frame(kind, 12, seed), "Mono16", 12, seed + 1, 0, time.time_ns())
        a, b = fp32.inspect(frame), bf16.inspect(frame)
        assert a.error is None and b.error is None
        scores.append(a.score)
        diffs.append(abs(a.score - b.score))
    assert max(scores) - min(scores) > 4 * BF16_SCORE_BOUND  # the frames really do score differently
    print(f"scores {min(scores):.3f}..{max(scores):.3f}; bf16 vs fp32 max |difference| {max(diffs):.4f}")
    assert max(diffs) <= BF16_SCORE_BOUND, diffs


def test_the_shipped_model_rejects_every_hostile_frame() -> None:
    """Frames unlike any part (dark, saturated, noise, one polarizer lit, half clipped) are far from the good parts
    the variation member knows: all above the threshold, in fp32 and bf16 (fail closed)."""
    for precision in ("fp32", "bf16"):
        det = DraemDetector(SHIPPED, "cpu", precision)
        inspector = Inspector(det, IMX250MZR)
        for seed, kind in enumerate(KINDS):
            result = inspector.inspect(Frame(hostile_frame(kind, 12, seed), "Mono16", 12, seed + 1, 0,
                                             time.time_ns()))
            assert result.error is None and result.score > det.threshold, (precision, kind, result.score)


def test_onnx_runtime_scores_like_torch_on_the_shipped_model() -> None:
    pytest.importorskip("onnxruntime")
    shipped = Path(__file__).parents[2] / "model" / "weights" / "default"
    torch_path = Inspector(DraemDetector(shipped, "cpu", "fp32"), IMX250MZR)
    onnx_path = Inspector(DraemDetector(shipped, "cpu", "onnx"), IMX250MZR)
    for seed, kind in enumerate(KINDS):
        frame = Frame(hostile_frame(kind, 8, seed), "Mono8", 8, seed + 1, 0, time.time_ns())
        a, b = torch_path.inspect(frame), onnx_path.inspect(frame)
        assert a.error is None and b.error is None
        assert abs(a.score - b.score) <= 1e-4 and float(np.abs(a.heatmap - b.heatmap).max()) <= 1e-3


def test_the_shipped_model_runs_fp32_under_auto() -> None:
    """Its int8 networks (`station quantize`, 2026-11-24) changed none of 90 validation decisions, but on the
    hostile frames above they scored the one-hot frame 0.18 where fp32 scored 0.51, across the threshold (0.26): a
    pass where fp32 rejects, on a frame unlike any part. So the shipped model comes without int8 networks and
    ``precision = "auto"`` runs fp32 (model/weights/README.md)."""
    shipped = Path(__file__).parents[2] / "model" / "weights" / "default"
    assert not shipped.with_name("default.int8").exists()
    assert DraemDetector(shipped, "cpu", "auto").precision == "fp32"
