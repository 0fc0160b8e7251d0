"""The torch path gives the numpy path's numbers (1e-5 full scale) for every method, input type and batch.

AoLP is compared on the circle and where it is well conditioned: (1) |(S1, S2)| >= MIN_MAG, since a float32
rounding difference in S1, S2 turns the angle arbitrarily when they are near 0; (2) away from |S1| = |S2|, where
OpenCV's polynomial atan2 switches branch with a 1.7e-4 rad step (both paths have the step; a last-bit
difference decides the side). Everywhere, |(S1, S2)| times the angle difference stays below 1e-5.
"""

from __future__ import annotations

import cv2
import numpy as np
import pytest

torch = pytest.importorskip("torch")

from model.priors import METHODS, compute_priors, normalize_mosaic, stokes_to_mosaic  # noqa: E402
from model.priors.testing import detailed_stokes  # noqa: E402
from model.priors.torch_ops import (  # noqa: E402
    TORCH_METHODS,
    compute_priors_torch,
    normalize_mosaic_torch,
    phase_torch,
)

ALL = ("intensity", "dolp", "aolp", "aolp_cos", "aolp_sin")
TOL = 1e-5
MIN_MAG = 1e-2
DEVICES = ["cpu"] + (["cuda"] if torch.cuda.is_available() else [])


def _mosaic(seed: int = 5, shape=(64, 96)) -> np.ndarray:
    return stokes_to_mosaic(*detailed_stokes(*shape, seed=seed))


def _assert_parity(numpy_priors, torch_priors) -> None:
    assert set(numpy_priors) == set(torch_priors)
    for key, ref in numpy_priors.items():
        got = torch_priors[key].cpu().numpy()
        assert got.dtype == np.float32 and got.shape == ref.shape, key
        assert np.isfinite(got).all(), key
        if key not in ("aolp", "aolp_cos", "aolp_sin"):
            np.testing.assert_allclose(got, ref, atol=TOL, rtol=0, err_msg=key)
    if "aolp" not in numpy_priors:
        return
    s1, s2 = numpy_priors["s1"], numpy_priors["s2"]
    mag = np.hypot(s1, s2)
    diff = np.abs(np.angle(np.exp(2j * (numpy_priors["aolp"].astype(np.float64) - torch_priors["aolp"].cpu().numpy()))))
    diff /= 2
    assert (mag * diff).max() < TOL
    sure = (mag >= MIN_MAG) & (np.abs(np.abs(s1) - np.abs(s2)) > 1e-5)
    assert diff[sure].max() < TOL
    for key in ("aolp_cos", "aolp_sin"):
        assert (mag * np.abs(numpy_priors[key] - torch_priors[key].cpu().numpy())).max() < TOL, key


def test_every_numpy_method_has_a_torch_twin():
    assert set(TORCH_METHODS) == set(METHODS)


@pytest.mark.parametrize("device", DEVICES)
@pytest.mark.parametrize("method", sorted(METHODS))
@pytest.mark.parametrize("kind", ["uint8", "uint16_12bit", "float32"])
def test_priors_match_numpy(method, kind, device):
    mosaic = _mosaic()
    if kind == "uint8":
        raw, bits = np.clip(np.rint(mosaic * 255), 0, 255).astype(np.uint8), None
        tensor = torch.from_numpy(raw)
    elif kind == "uint16_12bit":
        raw, bits = np.clip(np.rint(mosaic * 4095), 0, 4095).astype(np.uint16), 12
        tensor = torch.from_numpy(raw.astype(np.int32)).to(torch.uint16)
    else:
        raw, bits = mosaic, None
        tensor = torch.from_numpy(raw)
    _assert_parity(compute_priors(raw, method=method, priors=ALL, bit_depth=bits),
                   compute_priors_torch(tensor.to(device), method=method, priors=ALL, bit_depth=bits))


@pytest.mark.parametrize("device", DEVICES)
@pytest.mark.parametrize("method", sorted(METHODS))
def test_batched_input_matches_frame_by_frame(method, device):
    frames = np.stack([_mosaic(seed) for seed in range(3)])
    raw = np.clip(np.rint(frames * 255), 0, 255).astype(np.uint8)
    batch = compute_priors_torch(torch.from_numpy(raw).to(device), method=method, priors=ALL)
    for n in range(len(raw)):
        _assert_parity(compute_priors(raw[n], method=method, priors=ALL), {k: v[n] for k, v in batch.items()})


@pytest.mark.filterwarnings("ignore:overflow encountered in cast:RuntimeWarning")  # 1e300 -> Inf, on purpose
@pytest.mark.parametrize("method", sorted(METHODS))
def test_float_with_nan_inf_and_junk_bits_are_treated_alike(method):
    raw = _mosaic().astype(np.float64)
    raw[3, 5], raw[10, 11], raw[20, 0], raw[0, 7] = np.nan, np.inf, -np.inf, 1e300  # 1e300 is Inf in float32
    ref = compute_priors(raw, method=method, priors=ALL)
    got = compute_priors_torch(torch.from_numpy(raw), method=method, priors=ALL)
    _assert_parity(ref, got)
    norm = normalize_mosaic_torch(torch.from_numpy(raw))
    assert int(norm.n_nonfinite) == ref.n_nonfinite == 4
    assert np.array_equal(norm.invalid[0].numpy(), ref.invalid)

    codes = np.clip(np.rint(_mosaic() * 4095), 0, 4095).astype(np.uint16)
    codes[1, 1] = 40000  # junk above the 12 significant bits
    np_norm = normalize_mosaic(codes, bit_depth=12)
    t_norm = normalize_mosaic_torch(torch.from_numpy(codes.astype(np.int32)).to(torch.uint16), bit_depth=12)
    assert int(t_norm.n_out_of_range) == np_norm.n_out_of_range == 1
    assert int(t_norm.n_saturated) == np_norm.n_saturated
    np.testing.assert_array_equal(t_norm.data[0].numpy(), np_norm.data)


def test_only_requested_priors_and_two_dimensional_shapes():
    raw = np.zeros((4, 6), np.uint8)
    got = compute_priors_torch(torch.from_numpy(raw), priors=("intensity",))
    assert set(got) == set(compute_priors(raw, priors=("intensity",))) and got["s0"].shape == (4, 6)
    assert compute_priors_torch(torch.zeros(2, 4, 6), method="superpixel")["dolp"].shape == (2, 2, 3)


@pytest.mark.parametrize(("raw", "error", "match"), [
    (torch.zeros(5, 4, dtype=torch.uint8), ValueError, r"\(5, 4\)"),
    (torch.zeros(1, 1, 4, 4), ValueError, r"\(1, 1, 4, 4\)"),
    (torch.zeros(4, 4, dtype=torch.int64), TypeError, "int64"),
])
def test_bad_tensors_are_named_in_the_error(raw, error, match):
    with pytest.raises(error, match=match):
        compute_priors_torch(raw)
    with pytest.raises(ValueError, match="unknown demosaic method"):
        compute_priors_torch(torch.zeros(4, 4), method="nope")


def test_phase_is_opencvs_polynomial():
    rng = np.random.default_rng(0)
    special = np.array([0.0, -0.0, 1e-45, -1e-45, 1e-30, -1e-30, 1.0, -1.0, 3e38, -3e38, 1e-3], np.float32)
    pairs = np.array(np.meshgrid(special, special)).reshape(2, -1)
    x = np.concatenate([rng.normal(size=20000), rng.normal(size=2000) * 1e-20, pairs[0]]).astype(np.float32)
    y = np.concatenate([rng.normal(size=20000), rng.normal(size=2000) * 1e-20, pairs[1]]).astype(np.float32)
    x[:100] = y[:100]  # on the diagonal, where the polynomial switches branch
    ref = cv2.phase(x.reshape(1, -1), y.reshape(1, -1)).ravel()
    got = phase_torch(torch.from_numpy(x), torch.from_numpy(y)).numpy()
    np.testing.assert_allclose(got, ref, atol=2e-6, rtol=0)  # float32 last bits (OpenCV uses FMA)
    assert np.abs(ref - np.mod(np.arctan2(y, x), 2 * np.pi))[:20000].max() > 1e-4  # really not torch.atan2
