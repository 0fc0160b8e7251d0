"""Normal estimation: physics SfP on analytic spheres, the angular error, the learned net, its checkpoint."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
import torch

from model.normals.errors import NormalsCheckpointError, NormalsError
from model.normals.net import NormalNetConfig, NormalUNet, load_normal_net, save_normal_net, stack_inputs
from model.normals.sfp import (
    angular_error_deg,
    diffuse_dolp,
    sfp_normals,
    summarize_errors,
    view_directions,
    zenith_from_dolp,
)
from model.normals.train import NormalTrainConfig, mirror, normal_loss, prepare_sample, train_normal_net


def sphere(size: int = 64, fov_x_deg: float | None = 30.0, radius_frac: float = 0.8, n: float = 1.5):
    """A sphere on the optical axis filling ``radius_frac`` of the frame's half width: ground-truth normals,
    diffuse DoLP and AoLP (the forward model of the module docstring), mask and viewing directions."""
    view = view_directions((size, size), fov_x_deg).astype(np.float64)
    ray = -view  # from the camera into the scene
    if fov_x_deg is None:  # orthographic: rays along -z from the image plane, sphere of radius 1 at the origin
        half = 1 / radius_frac
        c = (np.arange(size) + 0.5) / size * 2 * half - half
        px, py = np.meshgrid(c, -c)
        r2 = px**2 + py**2
        mask = r2 < 1
        normal = np.stack([px, py, np.sqrt(np.clip(1 - r2, 0, None))], -1)
    else:  # camera at the origin, sphere centre on -z at distance d, radius chosen to fill radius_frac
        d = 10.0
        radius = d * math.sin(math.atan(radius_frac * math.tan(math.radians(fov_x_deg) / 2)))
        centre = np.array([0.0, 0.0, -d])
        b = ray @ centre
        disc = b**2 - (centre @ centre - radius**2)
        mask = disc > 0
        t = b - np.sqrt(np.clip(disc, 0, None))
        normal = (t[..., None] * ray - centre) / radius
    normal = np.where(mask[..., None], normal / np.linalg.norm(normal, axis=-1, keepdims=True), 0)
    cos_t = np.clip(np.einsum("hwc,hwc->hw", normal, view), 0, 1)
    dolp = np.where(mask, diffuse_dolp(np.arccos(cos_t), n), 0)
    p = normal - cos_t[..., None] * view  # azimuth direction: the normal's part perpendicular to the view
    aolp = np.where(mask, np.mod(np.arctan2(p[..., 1], p[..., 0]), np.pi), 0)
    return normal.astype(np.float32), dolp.astype(np.float32), aolp.astype(np.float32), mask, view.astype(np.float32)


@pytest.mark.parametrize("fov", [None, 30.0])
def test_sfp_recovers_sphere(fov):
    normal, dolp, aolp, mask, view = sphere(fov_x_deg=fov)
    est = sfp_normals(dolp, aolp, view, mask=mask)
    err = angular_error_deg(est, normal, mask)
    assert err.max() < 0.01, err.max()  # exact model, exact inversion: float32 rounding only
    assert np.all(est[~mask] == 0)
    assert np.allclose(np.linalg.norm(est[mask], axis=-1), 1, atol=1e-5)
    # noise at the level of a 16-spp render (DoLP +-0.01, AoLP +-2 deg): stated bound, median below 10 deg
    g = np.random.default_rng(0)
    noisy = sfp_normals(dolp + g.normal(0, 0.01, dolp.shape).astype(np.float32),
                        aolp + np.radians(g.normal(0, 2, aolp.shape)).astype(np.float32), view, mask=mask)
    stats = summarize_errors(angular_error_deg(noisy, normal, mask))
    assert stats["median_deg"] < 10, stats


def test_sfp_reference_rule_and_ambiguity():
    normal, dolp, aolp, mask, view = sphere()
    flipped = normal.copy()
    flipped[..., :2] *= -1  # the other azimuth candidate, with the same zenith
    ref = sfp_normals(dolp, aolp, view, mask=mask, resolve="reference", reference=normal)
    assert angular_error_deg(ref, normal, mask).max() < 0.01
    # a centre on the far left makes the outward rule pick the wrong candidate on the sphere's left half
    wrong = sfp_normals(dolp, aolp, view, mask=mask, center=(32.0, -1000.0))
    left = mask & (np.arange(64)[None, :] < 28)
    assert np.median(angular_error_deg(wrong, normal, left)) > 30
    with pytest.raises(NormalsError, match="reference"):
        sfp_normals(dolp, aolp, view, resolve="reference")
    with pytest.raises(NormalsError, match="resolve"):
        sfp_normals(dolp, aolp, view, resolve="nearest")


def test_zenith_inversion_exact_on_forward_model():
    theta = np.concatenate([np.linspace(0, np.pi / 2, 10001), np.random.default_rng(1).uniform(0, np.pi / 2, 1000)])
    for n in (1.3, 1.5, 1.8):
        back = zenith_from_dolp(diffuse_dolp(theta, n), n)
        assert np.abs(back - theta).max() < 1e-5, n  # float32 output; the lookup itself is ~1e-7 rad
    assert diffuse_dolp(np.pi / 2, 1.5) == pytest.approx(0.3846, abs=1e-4)
    z = zenith_from_dolp(np.array([-0.1, np.nan, np.inf, 0.0, 0.39, 1.0]))
    assert np.all(np.isfinite(z))
    assert z.tolist()[:2] == [0.0, 0.0] and z[3] == 0 and z[4] == z[5] == pytest.approx(np.pi / 2)
    with pytest.raises(NormalsError):
        diffuse_dolp(0.5, 1.0)


def test_view_directions():
    ortho = view_directions((4, 6))
    assert ortho.shape == (4, 6, 3) and np.all(ortho == [0, 0, 1])
    v = view_directions((5, 7), 40.0)
    assert np.allclose(v[2, 3], [0, 0, 1])  # frame centre
    assert v[0, 0, 0] > 0 and v[0, 0, 1] < 0  # top-left pixel: the camera lies right of and below it
    f = 3.5 / math.tan(math.radians(20))
    assert np.allclose(v[2, 6], np.array([-3.0, 0, f]) / math.hypot(3.0, f), atol=1e-6)
    full = view_directions((48, 64), 30.0)
    crop = view_directions((48, 64), 30.0, box=(8, 16, 32, 32))
    assert np.allclose(crop, full[8:40, 16:48], atol=1e-6)
    half = view_directions((48, 64), 30.0, box=(8, 16, 32, 32), size=16)  # 2x2 blocks: centres between pixels
    assert np.allclose(half[0, 0], (full[8:10, 16:18].mean((0, 1))) / np.linalg.norm(full[8:10, 16:18].mean((0, 1))),
                       atol=1e-4)


def test_angular_error_known_cases():
    a = np.array([[1, 0, 0], [1, 0, 0], [1, 0, 0], [0, 0, 2.0], [0, 0, 0], [np.nan, 0, 1], [1, 1e-9, 0]])
    b = np.array([[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, 0, 1.0], [0, 0, 1], [0, 0, 1], [1, 0, 0]])
    err = angular_error_deg(a, b)
    assert np.all(np.isfinite(err))
    assert err[:4] == pytest.approx([0, 90, 180, 0], abs=1e-9)
    assert err[4] == 90 and err[5] == 90  # zero or non-finite: no estimate, no NaN
    assert err[6] == pytest.approx(np.degrees(1e-9), rel=1e-3)  # atan2 keeps tiny angles (acos would give 0)
    img = np.zeros((2, 3, 3))
    img[..., 2] = 1
    m = np.array([[True, False, True], [False, False, True]])
    assert angular_error_deg(img, img, m).shape == (3,)
    assert angular_error_deg(img, img).shape == (2, 3)
    assert summarize_errors(np.array([]))["n_px"] == 0
    s = summarize_errors(np.array([0.0, 10.0, 20.0, 40.0]))
    assert s["mean_deg"] == 17.5 and s["median_deg"] == 15 and s["within_11.25"] == 0.5
    with pytest.raises(NormalsError):
        angular_error_deg(np.zeros((2, 3)), np.zeros((3, 3)))


def test_sfp_imports_without_torch():
    code = "import sys; sys.modules['torch'] = None; import model.normals.sfp, model.normals; print('ok')"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and "ok" in r.stdout, r.stderr


def _sphere_sample(size: int, fov: float, shift: int, radius_frac: float):
    normal, dolp, aolp, mask, view = sphere(size, fov, radius_frac)
    roll = (lambda a: np.roll(a, shift, axis=1))  # noqa: E731 (move the sphere: varied training samples)
    maps = {"intensity": roll(0.2 + 0.6 * np.clip(normal[..., 2], 0, 1)), "dolp": roll(dolp),
            "aolp_cos": roll(np.cos(2 * aolp)), "aolp_sin": roll(np.sin(2 * aolp))}
    return maps, roll(normal), roll(mask), view


def test_mirror_is_exact_for_polarization():
    maps, normal, mask, view = _sphere_sample(32, 30.0, 0, 0.7)
    x = torch.from_numpy(stack_inputs(maps, view))[None]
    n = torch.from_numpy(normal.transpose(2, 0, 1).copy())[None]
    m = torch.from_numpy(mask)[None]

    def sfp_of(xx: torch.Tensor, mm: torch.Tensor) -> np.ndarray:
        a = xx[0].numpy()
        aolp = np.mod(0.5 * np.arctan2(a[3], a[2]), np.pi)
        return sfp_normals(a[1], aolp, a[4:7].transpose(1, 2, 0), mask=mm[0].numpy())

    for lr, ud in ((True, False), (False, True), (True, True)):
        xm, nm, mm = mirror(x, n, m, lr, ud)
        err = angular_error_deg(sfp_of(xm, mm), nm[0].permute(1, 2, 0).numpy(), mm[0].numpy())
        assert err.max() < 0.05, (lr, ud, err.max())  # mirrored inputs give the mirrored normals


def test_prepare_sample_and_tiny_net_learns():
    torch.manual_seed(0)
    xs, ns, ms = [], [], []
    for k, (shift, rad) in enumerate([(0, 0.5), (6, 0.6), (-6, 0.45), (3, 0.55), (-3, 0.6), (8, 0.5)]):
        maps, normal, mask, _ = _sphere_sample(40, 30.0, shift, rad)
        # frame 40 x 40 viewed through a 40 x 40 "center" roi, resized to 32: what the station's crop does
        s = prepare_sample(maps, mask, 32, 30.0, normal)
        assert s["x"].shape == (7, 32, 32) and s["normal"].shape == (3, 32, 32) and s["mask"].shape == (32, 32)
        assert s["box"] == (0, 0, 40, 40) and k >= 0
        xs.append(s["x"])
        ns.append(s["normal"])
        ms.append(s["mask"])
    x, n, m = torch.stack(xs), torch.stack(ns), torch.stack(ms)
    cfg = NormalNetConfig(base_width=4, levels=2, input_size_px=32)
    res = train_normal_net(x, n, m, cfg, NormalTrainConfig(steps=40, batch_size=4, lr=5e-3, seed=0, device="cpu",
                                                              threads=1),
                           progress=False)
    assert res.steps == 40 and len(res.history) == 4
    assert res.history[-1][1] < 0.85 * res.history[0][1] and res.history[-1][1] < res.loss_first, res.history
    with torch.no_grad():
        out = res.net(x)
    assert torch.allclose(out.norm(dim=1), torch.ones(1), atol=1e-4)
    assert normal_loss(out, n, m) < res.history[0][1]
    assert float(normal_loss(n, n, m)) == pytest.approx(0, abs=1e-6)
    with pytest.raises(NormalsError):
        NormalTrainConfig()


def test_checkpoint_round_trip_and_missing_files(tmp_path):
    torch.manual_seed(0)
    net = NormalUNet(NormalNetConfig(base_width=4, levels=2, input_size_px=16))
    with torch.no_grad():
        net.head.weight.normal_()  # the head starts at zero: make the output depend on the weights
    pt, js = save_normal_net(tmp_path / "nn", net, "abc", {"steps": 3})
    loaded, meta = load_normal_net(tmp_path / "nn.pt")
    x = torch.rand(2, 7, 16, 16)
    x[:, 4:7] = torch.tensor([0.0, 0.0, 1.0]).view(1, 3, 1, 1)
    with torch.no_grad():
        assert torch.equal(net.eval()(x), loaded(x))
    assert meta["data_manifest_sha256"] == "abc" and meta["train"]["steps"] == 3 and not loaded.training
    js.rename(tmp_path / "moved.json")
    with pytest.raises(NormalsCheckpointError, match=r"nn\.json: normal-estimator sidecar missing"):
        load_normal_net(tmp_path / "nn")
    (tmp_path / "moved.json").rename(js)
    pt.unlink()
    with pytest.raises(NormalsCheckpointError, match=r"nn\.pt: weights file missing"):
        load_normal_net(tmp_path / "nn")
    with pytest.raises(NormalsError, match="multiple of"):
        NormalNetConfig(input_size_px=30, levels=2)
