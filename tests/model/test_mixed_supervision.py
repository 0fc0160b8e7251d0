"""Mixed supervision (rendered defects with their masks in DRAEM's batches): the batch, the masked reconstruction
loss, the training loop at rendered_fraction 0 against the published loop, resume, and a toy learning check."""

from __future__ import annotations

import math

import numpy as np
import pytest
import torch

from model.draem.anomaly import AnomalyConfig, synthesize
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.draem.errors import ModelError
from model.draem.evaluate import EvalData, evaluate
from model.draem.loss import draem_loss
from model.draem.mixed import TensorDefectData, draw_batch
from model.draem.preprocess import Normalizer
from model.draem.train import TensorData, TrainConfig, train
from tests.model.conftest import toy_priors

PRIORS = ("intensity", "dolp", "aolp")


@pytest.fixture
def one_thread():
    """One torch thread: with both cores shared, two threads ran these tiny convolutions several times slower
    (conftest restores the thread count)."""
    torch.set_num_threads(1)


def _cfg(fusion: str = "fused", size: int = 32) -> ModelConfig:
    return ModelConfig.from_preset("tiny", PRIORS, fusion, input_size_px=size)


def toy_defects(n: int, size: int = 32, seed: int = 100, paired: bool = False, dolp_step: float = 0.25,
                turn_deg: float = 45.0) -> TensorDefectData:
    """A 'rendered' defect kind on the toy part: a disc of radius 3-5 px inside the part where DoLP rises by
    ``dolp_step`` and AoLP turns by ``turn_deg``; with ``paired`` the clean render (the same sample without the
    disc) is kept."""
    clean, obj = toy_priors(n, size, seed)
    g = torch.Generator().manual_seed(seed + 1)
    yy, xx = torch.meshgrid(torch.arange(size), torch.arange(size), indexing="ij")
    masks = torch.zeros(n, size, size, dtype=torch.bool)
    for i in range(n):
        r = float(torch.empty(1).uniform_(3, 5, generator=g))
        cy, cx = (size / 2 + (torch.rand(2, generator=g) - 0.5) * size * 0.4).tolist()
        masks[i] = ((yy - cy) ** 2 + (xx - cx) ** 2 <= r * r) & obj[i]
    x = clean.clone()
    m = masks.unsqueeze(1)
    x[:, 1:2] = torch.where(m, (x[:, 1:2] + dolp_step).clamp(0, 1), x[:, 1:2])
    co, si = math.cos(math.radians(2 * turn_deg)), math.sin(math.radians(2 * turn_deg))
    c, s = x[:, 2:3], x[:, 3:4]  # (cos 2a, sin 2a) turned by 2 * turn_deg
    x[:, 2:3], x[:, 3:4] = torch.where(m, co * c - si * s, c), torch.where(m, si * c + co * s, s)
    return TensorDefectData(x, obj, masks, clean if paired else None)


def test_batch_targets_of_rendered_samples():
    x, obj = toy_priors(6, 32)
    good = TensorData(x, obj)
    for paired in (False, True):
        d = toy_defects(5, paired=paired)
        b = draw_batch(good, PRIORS, 6, torch.Generator().manual_seed(0), torch.Generator().manual_seed(1),
                       AnomalyConfig(), torch.device("cpu"), d, 2, torch.Generator().manual_seed(2))
        ridx = torch.randint(5, (2,), generator=torch.Generator().manual_seed(2))
        assert b.n_rendered == 2 and b.inputs.shape == (6, 4, 32, 32)
        assert torch.equal(b.inputs[4:], d.priors[ridx])
        assert torch.equal(b.mask[4:], d.defect_mask[ridx].float())  # discriminative target: the true masks
        if paired:
            assert torch.equal(b.target[4:], d.clean[ridx]) and b.recon_weight is None
        else:  # reconstruct the input itself, weight 0 on the defect, 1 on every synthetic sample
            assert torch.equal(b.target[4:], d.priors[ridx])
            assert torch.equal(b.recon_weight[4:], (~d.defect_mask[ridx]).float())
            assert torch.equal(b.recon_weight[:4], torch.ones(4, 32, 32))
    # the synthetic part of the batch is still DRAEM's synthesis (anomalies on some good samples)
    idx = torch.randint(6, (4,), generator=torch.Generator().manual_seed(0))
    syn = synthesize(x[idx], PRIORS, torch.Generator().manual_seed(1), AnomalyConfig(), obj[idx])
    assert torch.equal(b.inputs[:4], syn.augmented) and torch.equal(b.mask[:4], syn.mask)
    # no rendered samples: exactly the published draw
    b0 = draw_batch(good, PRIORS, 4, torch.Generator().manual_seed(0), torch.Generator().manual_seed(1),
                    AnomalyConfig(), torch.device("cpu"))
    assert torch.equal(b0.inputs, syn.augmented) and torch.equal(b0.target, x[idx]) and b0.recon_weight is None


def test_masked_reconstruction_ignores_defect_pixels():
    g = torch.Generator().manual_seed(0)
    clean = torch.rand(2, 3, 32, 32, generator=g)
    rec = torch.rand(2, 3, 32, 32, generator=g, requires_grad=True)
    logits = torch.randn(2, 2, 32, 32, generator=g)
    defect = torch.zeros(2, 32, 32, dtype=torch.bool)
    defect[0, 10:16, 12:20] = True
    w = (~defect).float()
    lt = draem_loss(clean, rec, logits, defect.float(), w)
    (lt.l2 + lt.ssim).backward()
    assert rec.grad[0, :, 10:16, 12:20].abs().max() == 0  # no gradient into the defect's reconstruction
    assert rec.grad[0, :, 20:, :].abs().max() > 0 and rec.grad[1].abs().max() > 0
    # anything inside the defect, in the target or the reconstruction, leaves the loss unchanged
    clean2, rec2 = clean.clone(), rec.detach().clone()
    clean2[0, :, 10:16, 12:20] = 5.0
    rec2[0, :, 10:16, 12:20] = -3.0
    lt2 = draem_loss(clean2, rec2, logits, defect.float(), w)
    before, after = lt.as_floats(), lt2.as_floats()
    assert after["l2"] == pytest.approx(before["l2"], rel=1e-6)
    assert after["ssim"] == pytest.approx(before["ssim"], rel=1e-6)
    assert after["focal"] == before["focal"]  # the discriminative term is never weighted
    # a weight of ones is the published loss
    ones = draem_loss(clean, rec.detach(), logits, defect.float(), torch.ones(2, 32, 32))
    plain = draem_loss(clean, rec.detach(), logits, defect.float())
    assert float(ones.total) == pytest.approx(float(plain.total), rel=1e-5)


def _reference_losses(cfg: ModelConfig, x: torch.Tensor, obj: torch.Tensor, tc: TrainConfig
                      ) -> tuple[list[float], Detector]:
    """The training loop as published and as it was before mixed supervision, written out step by step."""
    index_gen, synth_gen = torch.Generator().manual_seed(tc.seed), torch.Generator().manual_seed(tc.seed + 7)
    det = Detector(cfg, Normalizer.fit(x[:256]))
    det.init_weights(torch.Generator().manual_seed(tc.seed))
    det.to(memory_format=torch.channels_last)
    det.train()
    opt = torch.optim.Adam(det.parameters(), lr=tc.lr)
    sched = torch.optim.lr_scheduler.MultiStepLR(opt, [int(tc.steps * f) for f in tc.lr_milestones], tc.lr_gamma)
    losses = []
    for _ in range(tc.steps):
        idx = torch.randint(len(x), (tc.batch_size,), generator=index_gen)
        syn = synthesize(x[idx], cfg.priors, synth_gen, tc.anomaly, obj[idx])
        clean = det.normalize(x[idx]).contiguous(memory_format=torch.channels_last)
        aug = det.normalize(syn.augmented).contiguous(memory_format=torch.channels_last)
        total = torch.zeros(())
        for name, net in det.members.items():
            sl = det.member_slice(name)
            o = net(aug[:, sl])
            total = total + draem_loss(clean[:, sl], o.reconstruction, o.logits, syn.mask).total
        opt.zero_grad(set_to_none=True)
        total.backward()
        opt.step()
        sched.step()
        losses.append(float(total.detach()))
    return losses, det


def test_rendered_fraction_zero_is_the_published_loop_bit_for_bit(tmp_path, one_thread):
    x, obj = toy_priors(8, 32)
    tc = TrainConfig(steps=4, batch_size=4, eval_every=4, seed=3, device="cpu")
    cfg = _cfg("ensemble")
    res = train(cfg, TensorData(x, obj), tmp_path / "a", tc, progress=False)
    ref_losses, ref = _reference_losses(cfg, x, obj, tc)
    assert [h["loss"] for h in res.history if "loss" in h] == ref_losses
    got = res.detector.state_dict()
    assert all(torch.equal(got[k], v) for k, v in ref.state_dict().items())
    # rendered defects passed but not asked for (fraction 0): ignored, same result
    again = train(cfg, TensorData(x, obj), tmp_path / "b", tc, progress=False, defects=toy_defects(4))
    assert [h["loss"] for h in again.history if "loss" in h] == ref_losses


def test_training_sees_the_rendered_masks_and_resumes_exactly(tmp_path, monkeypatch, one_thread):
    import model.draem.train as T

    x, obj = toy_priors(8, 32)
    d = toy_defects(6)
    tc = dict(batch_size=4, eval_every=2, seed=5, rendered_fraction=0.5, device="cpu")
    seen: list[torch.Tensor] = []
    real = T.draem_loss

    def spy(clean, rec, logits, mask, recon_weight=None):
        seen.append(mask.detach().clone())
        return real(clean, rec, logits, mask, recon_weight)

    monkeypatch.setattr(T, "draem_loss", spy)
    straight = train(_cfg(), TensorData(x, obj), tmp_path / "a", TrainConfig(steps=3, **tc), progress=False,
                     defects=d)
    monkeypatch.setattr(T, "draem_loss", real)
    defect_gen = torch.Generator().manual_seed(5 + 13)  # the defect stream of rank 0 (= a single process)
    for mask in seen:
        ridx = torch.randint(len(d), (2,), generator=defect_gen)
        assert torch.equal(mask[2:], d.defect_mask[ridx].float())
    # stopped after one step, then resumed: the same losses (the defect stream is checkpointed)
    train(_cfg(), TensorData(x, obj), tmp_path / "b", TrainConfig(steps=3, max_minutes=1e-9, **tc), progress=False,
          defects=d)
    resumed = train(_cfg(), TensorData(x, obj), tmp_path / "b", TrainConfig(steps=3, **tc), progress=False,
                    defects=d)
    la = [h["loss"] for h in straight.history if "loss" in h]
    assert [h["loss"] for h in resumed.history if "loss" in h] == pytest.approx(la, rel=1e-5)


def test_rendered_fraction_must_leave_synthetic_anomalies_in_the_batch(tmp_path):
    assert TrainConfig(batch_size=8, rendered_fraction=0.25).n_rendered == 2
    assert TrainConfig(batch_size=8).n_rendered == 0
    with pytest.raises(ModelError, match=r"\[0, 1\)"):
        TrainConfig(rendered_fraction=1.0)
    with pytest.raises(ModelError, match="gives 0 rendered"):
        TrainConfig(batch_size=4, rendered_fraction=0.1)
    with pytest.raises(ModelError, match="gives 4 rendered"):
        TrainConfig(batch_size=4, rendered_fraction=0.9)
    x, obj = toy_priors(4, 32)
    with pytest.raises(ModelError, match="no rendered defective samples"):
        train(_cfg(), TensorData(x, obj), tmp_path, TrainConfig(steps=1, batch_size=4, rendered_fraction=0.5),
              progress=False)
    with pytest.raises(ModelError, match="do not match"):
        TensorDefectData(torch.zeros(2, 4, 8, 8), torch.zeros(2, 8, 8, dtype=torch.bool),
                         torch.zeros(2, 8, 9, dtype=torch.bool))


def _toy_gain(tmp_path, seed: int, paired: bool = False) -> tuple[float, float]:
    """Pixel AUROC on unseen parts with a faint toy defect (DoLP +0.03, AoLP turned 8 degrees) after 60 equal
    steps: (synthetic anomalies only, half of each batch rendered defects)."""
    x, obj = toy_priors(32, 32, seed=0)
    train_defects = toy_defects(32, seed=100, paired=paired, dolp_step=0.03, turn_deg=8.0)
    test = toy_defects(24, seed=200, dolp_step=0.03, turn_deg=8.0)
    gx, gobj = toy_priors(24, 32, seed=300)
    val = EvalData(torch.cat([gx, test.priors]), torch.cat([gobj, test.object_mask]),
                   torch.cat([torch.zeros_like(gobj), test.defect_mask]), torch.tensor([0] * 24 + [1] * 24))
    out = []
    for fraction in (0.0, 0.5):
        tc = TrainConfig(steps=60, batch_size=8, lr=2e-3, eval_every=60, seed=seed, rendered_fraction=fraction,
                         device="cpu")
        res = train(_cfg(), TensorData(x, obj), tmp_path / f"{seed}-{fraction}", tc, progress=False,
                    defects=train_defects if fraction else None)
        out.append(evaluate(res.detector, val).metrics["pixel_auroc"])
    return out[0], out[1]


def left_over(synthetic: float, mixed: float) -> float:
    """The share of the synthetic-only model's pixel-AUROC shortfall (1 - AUROC) that the mixed model leaves."""
    return (1.0 - mixed) / max(1.0 - synthetic, 1e-9)


def test_rendered_defects_raise_pixel_auroc_on_their_kind(tmp_path, one_thread):
    """Measured (seeds 0, 1, 2) on an AVX2 machine: synthetic only 0.81 / 0.83 / 0.79, mixed 1.00 / 0.90 / 0.99; seed
    0 on an AVX-512 machine (2026-11-29): 0.951 and 0.997. The same seed trains differently on another CPU's kernels,
    so the test asks for what both show: the rendered defects take away most of what synthetic anomalies leave."""
    synthetic, mixed = _toy_gain(tmp_path, seed=0)
    assert mixed > synthetic and left_over(synthetic, mixed) < 0.5, (synthetic, mixed)


@pytest.mark.slow
def test_rendered_defects_raise_pixel_auroc_over_seeds_and_with_paired_renders(tmp_path, one_thread):
    runs = [_toy_gain(tmp_path / str(s), seed=s) for s in (0, 1, 2)]
    assert all(mixed > synthetic for synthetic, mixed in runs) and np.mean([left_over(*r) for r in runs]) < 0.5, runs
    synthetic, mixed = _toy_gain(tmp_path / "paired", seed=0, paired=True)  # clean renders as the target
    assert mixed > synthetic and left_over(synthetic, mixed) < 0.5, (synthetic, mixed)


def test_state_saved_before_mixed_supervision_still_resumes_exactly(tmp_path, one_thread):
    x, obj = toy_priors(8, 32)
    tc = dict(batch_size=2, eval_every=2, seed=1, device="cpu")
    straight = train(_cfg(), TensorData(x, obj), tmp_path / "a", TrainConfig(steps=3, **tc), progress=False)
    train(_cfg(), TensorData(x, obj), tmp_path / "b", TrainConfig(steps=3, max_minutes=1e-9, **tc), progress=False)
    state_file = tmp_path / "b" / "last.state.pt"
    state = torch.load(state_file, weights_only=True)
    del state["defect_gen"]  # as written by the loop before mixed supervision
    torch.save(state, state_file)
    resumed = train(_cfg(), TensorData(x, obj), tmp_path / "b", TrainConfig(steps=3, **tc), progress=False)
    la = [h["loss"] for h in straight.history if "loss" in h]
    assert [h["loss"] for h in resumed.history if "loss" in h] == pytest.approx(la, rel=1e-5)
