import math

import torch

from model.draem.anomaly import AnomalyConfig, synthesize
from model.draem.perlin import perlin_masks, perlin_noise


def test_masks_are_deterministic_under_a_seed_and_differ_across_seeds():
    a = perlin_masks(8, 48, 80, torch.Generator().manual_seed(3))
    b = perlin_masks(8, 48, 80, torch.Generator().manual_seed(3))
    c = perlin_masks(8, 48, 80, torch.Generator().manual_seed(4))
    assert a.shape == (8, 48, 80) and a.dtype == torch.bool
    assert torch.equal(a, b) and not torch.equal(a, c)


def test_mask_statistics():
    m = perlin_masks(256, 64, 64, torch.Generator().manual_seed(0)).float()
    frac = m.mean((1, 2))
    # sqrt(2) * Perlin > 0.5 covers a few percent of the image on average; some masks are empty, none full
    assert 0.02 < float(frac.mean()) < 0.15
    assert float(frac.max()) < 0.6
    assert float((frac > 0).float().mean()) > 0.5


def test_noise_scale_controls_feature_size():
    g = torch.Generator().manual_seed(1)
    ones = torch.ones(16)
    coarse = perlin_noise(ones, ones, 64, 64, g)
    fine = perlin_noise(ones * 32, ones * 32, 64, 64, g)
    tv = lambda n: float((n[:, 1:] - n[:, :-1]).abs().mean())  # noqa: E731
    assert tv(fine) > 5 * tv(coarse)
    assert float(coarse.abs().max()) <= math.sqrt(2) + 1e-4


def test_synthesis_is_channel_aware_and_stays_on_the_object(toy):
    x, obj = toy(16, 64)
    g = torch.Generator().manual_seed(0)
    syn = synthesize(x, ("intensity", "dolp", "aolp"), g, AnomalyConfig(anomaly_fraction=1.0), obj)
    m = syn.mask.bool()
    assert m.any() and not (m & ~obj).any()  # restricted to the object
    assert torch.equal(syn.label.bool(), m.flatten(1).any(1))
    outside = ~m.unsqueeze(1).expand_as(x)
    assert torch.equal(syn.augmented[outside], x[outside])
    norm = torch.linalg.vector_norm(syn.augmented[:, 2:4], dim=1)
    assert torch.allclose(norm, torch.ones_like(norm), atol=1e-5)  # AoLP stays on the circle
    assert float(syn.augmented[:, :2].min()) >= 0 and float(syn.augmented[:, :2].max()) <= 1
    assert (syn.augmented[:, 0][m] != x[:, 0][m]).float().mean() > 0.9


def test_half_of_the_samples_stay_clean_and_normals_stay_unit():
    n, s = 64, 32
    normals = torch.nn.functional.normalize(torch.randn(n, 3, s, s) + torch.tensor([0, 0, 3.0]).view(1, 3, 1, 1), dim=1)
    syn = synthesize(normals, ("normal",), torch.Generator().manual_seed(2), AnomalyConfig())
    assert 0.25 < float((syn.label == 0).float().mean()) < 0.8
    norm = torch.linalg.vector_norm(syn.augmented, dim=1)
    assert torch.allclose(norm, torch.ones_like(norm), atol=1e-5)


def test_a_signed_prior_keeps_its_negative_values_and_its_anomalies_span_minus_one_to_one():
    """The tilt priors lie in [-1, 1]: synthesis must not clip them to [0, 1] like intensity."""
    g = torch.Generator().manual_seed(0)
    x = torch.full((8, 2, 32, 32), -0.4)
    x[:, 0] = 0.5  # intensity
    out = synthesize(x, ("intensity", "tilt_x"), g, AnomalyConfig(anomaly_fraction=1.0))
    tilt, m = out.augmented[:, 1], out.mask.bool()
    assert torch.equal(tilt[~m], x[:, 1][~m])  # untouched outside the anomalies, negative values kept
    assert float(tilt.min()) >= -1.0 and float(tilt.max()) <= 1.0 and float(tilt[m].min()) < -0.4
