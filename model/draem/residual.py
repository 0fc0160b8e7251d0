"""The residual networks: small segmentation networks that read what the variation model leaves of a part.

The variation model (``model.draem.variation``) registers each part, takes the line's shared appearance out and
divides what is left by the good parts' spread at each pixel: ``signed_z``, per channel, about N(0, 1) on a good
part where render or sensor noise dominates, structured where the part's own variation does. Its decision, the box
average of the largest channel's |z| against the good parts at that place, treats every leftover alike. A defect
leaves a shape (a dent a tilt, signed and opposite across it in the Stokes components; a chip an edge; a stain a
patch in intensity) that a good part's leftovers do not; a network can learn which is which from examples.

Training (``train_residual``): the good training parts' signed z maps, each from the appearance fitted without
it (``VariationModel.fit``'s return: what an unseen good part looks like), half of them with a synthetic anomaly
added in z space (``synthetic_anomaly``: a blob, a line or a noise patch, of a signed amplitude per channel or as a
tilt's signed pattern: shapes nobody rendered, so that the networks also mark defects of kinds they never saw),
and the training split's rendered defective parts with their masks registered as the frames are. A quarter of each
batch is rendered defects. Random 64 x 96 crops; per-pixel weighted cross-entropy plus an image term on the top
``TOP_K`` logits. Input channels: the C signed z channels, the part region, and the log of the variation model's
``window_spread`` standardised over the region (where good parts vary more: each place against itself, as the
variation model's own statistic).

Score: each member's image score is the mean of its ``TOP_K`` highest pixel probabilities over the eroded judged
part, put in robust standard deviations above the good validation parts (``calibration``: median, 1.4826 MAD per
member), then averaged over members (an ensemble of seeds). Measured on the validation set (600 parts, 370 good)
against the variation model's own statistic: docs/results/2026-11-25-residual-networks.md.

As the variation model's second look (rule 49, docs/results/2026-11-29-second-look.md; ``look``): the networks are
asked only about a part above the second look's gate, and their finding is the mean of the members' ``TOP_K``
highest logits (the probabilities saturate at 1: calibrated, they top out below the window's 1 % threshold), in
robust SD over the good validation parts. That finding and the variation model's score, each divided by its own 1 %
threshold on the good validation parts, are put side by side; the part scores the larger (``look_score``).
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable
from pathlib import Path
from typing import NamedTuple

import cv2
import numpy as np
import torch
import torch.nn.functional as F
from torch import nn

from .errors import ModelError

log = logging.getLogger(__name__)

WIDTH = 16
"""Channels of the first level (the second and third have twice that): about 70 k parameters per member."""

TOP_K = 10
"""Pixels averaged for a member's image score (and its image loss): a defect of a few pixels counts, one hot
pixel does not decide alone."""

CROP = (64, 96)
"""Training crop (height, width) at the model input; the networks are fully convolutional and score whole frames."""

RENDERED_SHARE = 0.25
"""Share of each batch drawn from the rendered defective parts (the rest good parts, half of them with a synthetic
anomaly)."""

LOOK_FALSE_REJECT = 0.01
"""The second look puts the networks' finding and the variation model's score side by side in units of their own
threshold at this rate of good validation parts rejected (the line's operating point)."""

LOOK = ("location", "spread", "threshold", "variation_threshold")
"""The entries of ``ResidualDetector.look`` (float64), in order: the median and spread (1.4826 MAD) of the mean top
logits over the good validation parts, the networks' threshold in those robust SD and the variation model's (in
the window's robust SD, ``model.draem.second_look``), each at ``LOOK_FALSE_REJECT``. The threshold inf: no look
(the networks decide, or only report)."""

STATE_EVERY = 250
"""Training steps between a member's resume states (``train_member``'s ``state``): at 0.2-0.4 s a step on 2 cores,
an interrupted training loses at most a minute or two."""

NO_LOOK = (0.0, 1.0, float("inf"), float("inf"))
"""``ResidualDetector.look`` of networks that are no second look (``LOOK``)."""

BLEND = ("weight", "window_threshold", "finding_threshold")
"""The entries of ``ResidualDetector.blend`` (float64), in order: the window's share of the blend (0: no blend, the
cascade), and the 1 % thresholds (``BLEND_FALSE_REJECT``) of the variation model's score without the look and of the
networks' finding (``look_score``), both in the window's units, on the good parts of the set the blend was calibrated
on (``station blend``: the threshold set). Rule ``blended``."""

NO_BLEND = (0.0, float("inf"), float("inf"))
"""``ResidualDetector.blend`` of a look without a blend: the cascade (and files from before the blend load so)."""

BLEND_FALSE_REJECT = 0.01
"""The blend puts each finding over its own threshold at this rate of good parts rejected (stop 119's rule, read on
fresh seeds 1238-1239: docs/results/2026-12-07-blend-rates.md)."""

BLEND_WEIGHT = 0.25
"""The window's share of the blend (``station blend --weight``): chosen by stop 119's plan on sets read before
(docs/results/2026-12-06-look-mean.md), then held fixed and read on fresh seeds 1238-1239."""

CHECK_MARGIN = 1e-4
"""How far (window units) the variation model's score must lie above its window's largest value to count as a check's
finding (the shape, outline or frame checks raise the score; the window alone gives it exactly)."""


def blended(score: torch.Tensor, window: torch.Tensor, found: torch.Tensor, weight: float, window_threshold: float,
            finding_threshold: float) -> torch.Tensor:
    """The blend's score (rule of stop 119, docs/results/2026-12-06-look-mean.md; read on fresh sets in
    docs/results/2026-12-07-blend-rates.md), all in the window's units: (N,) ``score`` the variation model's score
    with its checks and without the look, (N,) ``window`` its window's largest value, (N,) ``found`` the networks'
    finding (``ResidualDetector.look_score``, in window units). With t_w, t_f the two thresholds and c the checks'
    part (``score`` where it lies above ``window`` by more than ``CHECK_MARGIN``, else 0), a part scores
    t_w * max(weight * score / t_w + (1 - weight) * found / t_f, c / t_w): a quarter (the shipped weight) of the
    window's finding and three quarters of the network's, each over its own 1 % threshold, and a check's finding
    whole. float64."""
    s, f = score.double(), found.double().to(score.device)
    checks = torch.where(s > window.double().to(s.device) + CHECK_MARGIN, s, torch.zeros_like(s))
    mix = weight * s / window_threshold + (1.0 - weight) * f / finding_threshold
    return window_threshold * torch.maximum(mix, checks / window_threshold)

UNJUDGEABLE_Z = 1e3
"""Decision score (robust SD) of a frame the variation model cannot judge: its noise level beyond ``NOISE_CAP`` (a
frame nothing like the fitted line's parts: hostile, black, saturated, another part) or more than ``MAX_HIDDEN`` of
the part hidden by highlights. The networks never saw such inputs, so their finding there is not trusted: the part
is rejected, and its frame checks (``noise_level``, ``highlight_fraction``) say why. The variation model's own
decision rejects these parts by its statistic."""


class ResidualOutput(NamedTuple):
    """Per frame of N: ``map`` (N, H, W) the members' mean probability of a defect; ``score`` (N,) the calibrated image
    score (robust SD above the good validation parts, mean over members)."""

    map: torch.Tensor
    score: torch.Tensor


class ResidualNet(nn.Module):
    """A three-level U-Net: (N, in_channels, H, W) -> (N, H, W) logits. H, W any size (pooled twice)."""

    def __init__(self, in_channels: int, width: int = WIDTH) -> None:
        super().__init__()

        def block(i: int, o: int) -> nn.Sequential:
            return nn.Sequential(nn.Conv2d(i, o, 3, padding=1), nn.ReLU(), nn.Conv2d(o, o, 3, padding=1), nn.ReLU())

        self.e1, self.e2, self.e3 = block(in_channels, width), block(width, 2 * width), block(2 * width, 2 * width)
        self.d2, self.d1 = block(4 * width, 2 * width), block(3 * width, width)
        self.out = nn.Conv2d(width, 1, 1)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        a = self.e1(x)
        b = self.e2(F.max_pool2d(a, 2))
        c = self.e3(F.max_pool2d(b, 2))
        b = self.d2(torch.cat([b, F.interpolate(c, size=b.shape[2:])], 1))
        a = self.d1(torch.cat([a, F.interpolate(b, size=a.shape[2:])], 1))
        return self.out(a)[:, 0]


class ResidualDetector(nn.Module):
    """``members`` ResidualNets of ``channels`` + 2 inputs and their ``calibration`` (members, 2): median and spread
    of each member's image score on good validation parts."""

    def __init__(self, channels: int, members: int) -> None:
        super().__init__()
        if members < 1:
            raise ModelError(f"residual networks: members must be >= 1, got {members}")
        self.members = nn.ModuleList(ResidualNet(channels + 2) for _ in range(members))
        self.register_buffer("calibration", torch.tensor([[0.0, 1.0]] * members))
        self.register_buffer("look", torch.tensor(NO_LOOK, dtype=torch.float64))
        self.register_buffer("blend", torch.tensor(NO_BLEND, dtype=torch.float64))

    @property
    def looks(self) -> bool:
        """Whether the networks are the variation model's second look (``look`` set by ``calibrate_look``)."""
        return bool(torch.isfinite(self.look).all())

    @property
    def blends(self) -> bool:
        """Whether the look is blended (``blend``, set by ``calibrate_blend``): the networks are asked about every
        part, not only those above the second look's gate."""
        return self.looks and float(self.blend[0]) > 0

    @staticmethod
    def inputs(signed: torch.Tensor, region: torch.Tensor, window_spread: torch.Tensor) -> torch.Tensor:
        """(N, C, H, W) ``signed_z`` maps, (H, W) region and (H, W) window spread of the variation model -> the
        networks' input (N, C + 2, H, W): the maps, the region, the log spread standardised over the region (zero
        off it). Finite for finite inputs."""
        reg = region.bool()
        ls = torch.log(window_spread.float().clamp_min(1e-6))
        sel = ls[reg] if bool(reg.any()) else ls.flatten()
        ls = torch.where(reg, (ls - sel.mean()) / sel.std().clamp_min(1e-6), torch.zeros_like(ls))
        n = signed.shape[0]
        extra = torch.stack([reg.float(), ls]).to(signed.device).expand(n, 2, *reg.shape)
        return torch.cat([signed.float(), extra], 1)

    @staticmethod
    def member_scores(prob: torch.Tensor, judged: torch.Tensor) -> torch.Tensor:
        """(N, H, W) probabilities and (N, H, W) bool pixels to judge -> (N,) mean of the ``TOP_K`` highest there
        (over the whole map when none is judged: fail closed, a frame with nothing judged is not passed by an empty
        maximum)."""
        j = judged.bool() | ~judged.flatten(1).any(1).view(-1, 1, 1)
        v = prob.masked_fill(~j, -1.0).flatten(1)
        top = v.topk(min(TOP_K, v.shape[1]), 1).values
        return torch.where(top >= 0, top, torch.zeros_like(top)).sum(1) / (top >= 0).sum(1).clamp_min(1)

    @torch.no_grad()
    def raw(self, x: torch.Tensor, judged: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """Inputs (N, C + 2, H, W) and judged (N, H, W) -> ((N, H, W) mean probability, (members, N) raw scores)."""
        probs = [torch.sigmoid(m(x)) for m in self.members]
        return torch.stack(probs).mean(0), torch.stack([self.member_scores(p, judged) for p in probs])

    @torch.no_grad()
    def predict(self, x: torch.Tensor, judged: torch.Tensor) -> ResidualOutput:
        """``raw``, each member's score calibrated and averaged (``ResidualOutput``)."""
        prob, raw = self.raw(x, judged)
        loc, spread = self.calibration[:, 0:1], self.calibration[:, 1:2]
        return ResidualOutput(prob, ((raw - loc) / spread).mean(0))

    @torch.no_grad()
    def top_logits(self, x: torch.Tensor, judged: torch.Tensor) -> torch.Tensor:
        """Inputs (N, C + 2, H, W) and judged (N, H, W) -> (N,) the mean over members of the mean of their ``TOP_K``
        highest logits over the judged pixels (the whole map when none is judged: fail closed), float64, finite (a
        NaN reads as 1e6: the part is raised)."""
        j = judged.bool() | ~judged.flatten(1).any(1).view(-1, 1, 1)
        k = min(TOP_K, j[0].numel())
        out = [m(x).masked_fill(~j, -torch.inf).flatten(1).topk(k, 1).values.mean(1) for m in self.members]
        return torch.nan_to_num(torch.stack(out).mean(0).double(), nan=1e6, posinf=1e6, neginf=-1e6)

    def calibrate_look(self, top_logits: torch.Tensor, variation_scores: np.ndarray) -> None:
        """Set ``look`` from the good validation parts' (N,) ``top_logits`` and (N,) variation scores in the window's
        robust SD (module docstring; ``LOOK``)."""
        from .metrics import false_reject_threshold
        from .second_look import robust_location_spread

        loc, spread = robust_location_spread(top_logits.double().numpy())
        t = false_reject_threshold((top_logits.double().numpy() - loc) / spread, LOOK_FALSE_REJECT)
        tv = false_reject_threshold(np.asarray(variation_scores, np.float64), LOOK_FALSE_REJECT)
        if not (t > 0 and tv > 0):
            raise ModelError(f"residual networks' look: the 1 % thresholds on the good validation parts must be > 0, "
                             f"got {t:.3g} (networks) and {tv:.3g} (variation model)")
        self.look.copy_(torch.tensor([loc, spread, t, tv], dtype=torch.float64))

    def look_score(self, top_logits: torch.Tensor) -> torch.Tensor:
        """(N,) ``top_logits`` -> (N,) the networks' finding in the variation model's robust SD: its robust SD over
        its own threshold, times the variation model's threshold (so that the larger of the two compares each against
        its own threshold)."""
        loc, spread, t, tv = (float(v) for v in self.look)
        return (top_logits.double() - loc) / spread / t * tv

    def calibrate_blend(self, weight: float, scores: np.ndarray, found: np.ndarray) -> None:
        """Set ``blend`` (``BLEND``) from the window's share ``weight`` in (0, 1] and the good parts' (N,) variation
        scores without the look and (N,) ``look_score`` findings, both in window units; ModelError without a look,
        for a weight out of range, or for a threshold not > 0 (the blend divides by both)."""
        from .metrics import false_reject_threshold

        if not self.looks:
            raise ModelError("the blend weighs the networks' finding as the second look: they are no look (station "
                             "residual --second-look)")
        if not 0.0 < weight <= 1.0:
            raise ModelError(f"blend weight (the window's share) must be in (0, 1], got {weight}")
        t_w = false_reject_threshold(np.asarray(scores, np.float64), BLEND_FALSE_REJECT)
        t_f = false_reject_threshold(np.asarray(found, np.float64), BLEND_FALSE_REJECT)
        if not (t_w > 0 and t_f > 0 and math.isfinite(t_w) and math.isfinite(t_f)):
            raise ModelError(f"blend: the 1 % thresholds on the good parts must be > 0, got {t_w:.3g} (window) and "
                             f"{t_f:.3g} (networks)")
        self.blend.copy_(torch.tensor([weight, t_w, t_f], dtype=torch.float64))

    def blend_score(self, score: torch.Tensor, window: torch.Tensor, found: torch.Tensor) -> torch.Tensor:
        """``blended`` with this look's ``blend``."""
        weight, t_w, t_f = (float(v) for v in self.blend)
        return blended(score, window, found, weight, t_w, t_f)

    def look_level(self, found: torch.Tensor) -> torch.Tensor:
        """(N,) the networks' finding in the window's units -> (N,) over this blend's finding threshold (1 where the
        network alone would reject), float32: the ``look_level`` frame check."""
        return (found / float(self.blend[2])).float()

    def calibrate(self, raw: torch.Tensor) -> None:
        """Set ``calibration`` from (members, N) raw scores of good validation parts (at least 2)."""
        if raw.shape[1] < 2:
            raise ModelError("calibrating the residual networks needs good validation parts (at least 2)")
        med = raw.double().median(1).values
        mad = (raw.double() - med[:, None]).abs().median(1).values * 1.4826
        self.calibration.copy_(torch.stack([med, mad.clamp_min(1e-6)], 1).float())

    def check(self) -> None:
        """ModelError unless every weight and calibration is finite and every spread > 0."""
        for name, t in [*self.named_parameters(), ("calibration", self.calibration)]:
            if not bool(torch.isfinite(t).all()):
                raise ModelError(f"residual networks: {name} has NaN or Inf values")
        if not bool((self.calibration[:, 1] > 0).all()):
            raise ModelError("residual networks: a calibration spread is not > 0")
        if not bool((self.look[1:] > 0).all()) or bool(torch.isnan(self.look).any()):
            raise ModelError("residual networks: look needs a spread and thresholds > 0")
        weight, t_w, t_f = (float(v) for v in self.blend)
        if not (weight == 0.0 or (0.0 < weight <= 1.0 and self.looks and 0 < t_w < math.inf and 0 < t_f < math.inf)):
            raise ModelError(f"residual networks: blend {[weight, t_w, t_f]} needs a look, a weight in (0, 1] and "
                             f"finite thresholds > 0 (or weight 0: none)")


def shape_mask(rng: np.random.Generator, judged: np.ndarray) -> np.ndarray | None:
    """A random shape inside ``judged`` (H, W) as a float32 (H, W) mask: an ellipse (1.5-12 px semi-axes), a line
    (8-50 px long, 1-3 px wide) or a patch of smooth noise above 1 SD, at a judged place; None when no place gives
    3 judged pixels in 20 tries. The shapes of ``synthetic_anomaly``."""
    h, w = judged.shape
    for _ in range(20):
        cy, cx = int(rng.integers(0, h)), int(rng.integers(0, w))
        if not judged[cy, cx]:
            continue
        m = np.zeros((h, w), np.float32)
        kind = int(rng.integers(3))
        if kind == 0:
            axes = (int(rng.uniform(1.5, 12)), int(rng.uniform(1.5, 12)))
            cv2.ellipse(m, (cx, cy), axes, float(rng.uniform(0, 180)), 0, 360, 1.0, -1)
        elif kind == 1:
            length, a = rng.uniform(8, 50), rng.uniform(0, np.pi)
            dx, dy = length / 2 * np.cos(a), length / 2 * np.sin(a)
            cv2.line(m, (int(cx - dx), int(cy - dy)), (int(cx + dx), int(cy + dy)), 1.0, int(rng.integers(1, 4)))
        else:
            noise = cv2.GaussianBlur(rng.standard_normal((h, w)).astype(np.float32), (0, 0), rng.uniform(2, 6))
            r = int(rng.integers(6, 25))
            box = np.zeros((h, w), bool)
            box[max(cy - r, 0):cy + r, max(cx - r, 0):cx + r] = True
            m = ((noise > noise.std()) & box).astype(np.float32)
        m *= judged
        if m.sum() >= 3:
            return m
    return None


def synthetic_anomaly(rng: np.random.Generator, z: np.ndarray, judged: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """One synthetic anomaly added to signed z maps ``z`` (C, H, W) inside ``judged`` (H, W) -> (z copy, (H, W) float
    mask). Shape: ``shape_mask``; amplitude per channel uniform in +-(0.5-4) z, either flat over the shape or as a
    tilt's signed pattern (the shape's gradient along a random direction, as a dent shows in the Stokes
    components). Channels that are zero everywhere (not features) stay zero. No change when no place fits."""
    m = shape_mask(rng, judged)
    if m is None:
        return z, np.zeros(judged.shape, np.float32)
    live = np.abs(z).reshape(len(z), -1).max(1) > 0
    amp = (rng.uniform(-1, 1, len(z)) * rng.uniform(0.5, 4.0) * live).astype(np.float32)
    if rng.random() < 0.5:
        gy, gx = np.gradient(cv2.GaussianBlur(m, (0, 0), 1.5))
        a = rng.uniform(0, 2 * np.pi)
        pattern = np.cos(a) * gx + np.sin(a) * gy
        pattern = pattern / (np.abs(pattern).max() + 1e-6)
        soft = np.abs(pattern)
    else:
        pattern = soft = cv2.GaussianBlur(m, (0, 0), 0.7)
    out = z + amp[:, None, None] * (pattern * judged)[None]
    return out.astype(np.float32), ((soft > 0.25) & judged).astype(np.float32)


def training_loss(logit: torch.Tensor, mask: torch.Tensor, inside: torch.Tensor) -> torch.Tensor:
    """A member's loss on a batch: per-pixel logits (N, H, W) against the anomaly ``mask`` (N, H, W, 0/1) on the
    pixels ``inside`` the part (N, H, W bool), binary cross-entropy with anomalies weighted 5; plus half the image
    loss, the mean of the ``TOP_K`` largest logits inside against whether the mask has any anomaly."""
    pix = F.binary_cross_entropy_with_logits(logit[inside], mask[inside], pos_weight=torch.tensor(5.0))
    top = logit.masked_fill(~inside, -30.0).flatten(1).topk(TOP_K, 1).values.mean(1)
    img = F.binary_cross_entropy_with_logits(top, (mask.flatten(1).amax(1) > 0).float())
    return pix + 0.5 * img


def seeded_init(net: nn.Module, seed: int) -> None:
    """PyTorch's default initialisation of every convolution of ``net`` (Kaiming-uniform weights with a = sqrt(5),
    biases U(-1/sqrt(fan_in), 1/sqrt(fan_in))), drawn from ``seed`` alone. A member's start was the global
    generator's at its construction, so the same seed trained another network after other code had drawn from it
    (test_residual_look's look once raised no score that way); the global generator is not touched."""
    g = torch.Generator().manual_seed(seed)
    with torch.no_grad():
        for m in net.modules():
            if isinstance(m, nn.Conv2d):
                nn.init.kaiming_uniform_(m.weight, a=math.sqrt(5), generator=g)
                if m.bias is not None:
                    bound = 1.0 / math.sqrt(m.weight[0].numel())
                    m.bias.uniform_(-bound, bound, generator=g)


def train_member(net: ResidualNet, good: np.ndarray, defects: np.ndarray, masks: np.ndarray, steps: int, seed: int,
                 batch: int = 16, lr: float = 1e-3, progress: Callable[[int, float], None] | None = None,
                 state: Path | None = None, every: int = STATE_EVERY) -> None:
    """Train one member on network inputs: ``good`` (N, C + 2, H, W) of good parts, ``defects`` (M, C + 2, H, W)
    of rendered defective parts with ``masks`` (M, H, W) (M may be 0). Adam at ``lr``, divided by 5 at 80 % of
    ``steps``; ``progress(step, loss)`` every 250 steps and at the last. ``state``: a file the training's state
    (weights, optimiser, schedule, random generator) is written to every ``every`` steps and at the end; when it
    exists, training continues from it with an uninterrupted run's draws and schedule (a state of another training,
    by its shapes, steps, seed, batch or rate, is refused: ModelError naming the file)."""
    rng = np.random.default_rng(seed)
    seeded_init(net, seed)
    opt = torch.optim.Adam(net.parameters(), lr)
    sched = torch.optim.lr_scheduler.MultiStepLR(opt, [int(steps * 0.8)], 0.2)
    recipe = {"good": list(good.shape), "defects": list(defects.shape), "masks": list(masks.shape), "steps": steps,
              "seed": seed, "batch": batch, "lr": lr}
    start = _resume(state, recipe, net, opt, sched, rng) if state is not None and state.is_file() else 0
    if start:
        log.info("%s: resuming at step %d of %d", state, start, steps)
    n_def = round(batch * RENDERED_SHARE) if len(defects) else 0
    ch, cw = min(CROP[0], good.shape[2]), min(CROP[1], good.shape[3])
    net.train()
    for step in range(start, steps):
        xb, mb = [], []
        for k in range(batch):
            if k < n_def:
                i = int(rng.integers(len(defects)))
                x, m = defects[i], masks[i].astype(np.float32)
            else:
                x, m = good[int(rng.integers(len(good)))], np.zeros(good.shape[2:], np.float32)
                if rng.random() < 0.5:
                    z, m = synthetic_anomaly(rng, x[:-2], x[-2] > 0)
                    x = np.concatenate([z, x[-2:]])
            y0, x0 = int(rng.integers(0, x.shape[1] - ch + 1)), int(rng.integers(0, x.shape[2] - cw + 1))
            xb.append(x[:, y0:y0 + ch, x0:x0 + cw])
            mb.append(m[y0:y0 + ch, x0:x0 + cw])
        xt, mt = torch.from_numpy(np.stack(xb)), torch.from_numpy(np.stack(mb))
        loss = training_loss(net(xt), mt, xt[:, -2] > 0)
        opt.zero_grad()
        loss.backward()
        opt.step()
        sched.step()
        if progress is not None and (step % 250 == 0 or step == steps - 1):
            progress(step, loss.item())
        if state is not None and ((step + 1) % every == 0 or step + 1 == steps):
            _save_state(state, recipe, step + 1, net, opt, sched, rng)
    net.eval()


def _save_state(path: Path, recipe: dict, step: int, net: ResidualNet, opt: torch.optim.Optimizer,
                sched: torch.optim.lr_scheduler.MultiStepLR, rng: np.random.Generator) -> None:
    """Write a member's training state after ``step`` steps, atomically (a kill mid-write keeps the last one)."""
    tmp = path.with_name(path.name + ".tmp")
    torch.save({"recipe": recipe, "step": step, "net": net.state_dict(), "opt": opt.state_dict(),
                "sched_epoch": sched.last_epoch, "rng": rng.bit_generator.state}, tmp)
    tmp.replace(path)


def _resume(path: Path, recipe: dict, net: ResidualNet, opt: torch.optim.Optimizer,
            sched: torch.optim.lr_scheduler.MultiStepLR, rng: np.random.Generator) -> int:
    """Restore a member's training state from ``path`` (``_save_state``); the step to continue from."""
    try:
        st = torch.load(path, map_location="cpu", weights_only=True)
        saved = st["recipe"]
    except Exception as exc:
        first = str(exc).splitlines()[0] if str(exc) else ""
        raise ModelError(f"{path}: cannot resume from it ({type(exc).__name__}: {first}); delete it to train this "
                         f"network from the start") from None
    if saved != recipe:
        diff = ", ".join(f"{k} {saved.get(k)} -> {v}" for k, v in recipe.items() if saved.get(k) != v)
        raise ModelError(f"{path}: the resume state of another training ({diff}); delete it or write elsewhere")
    net.load_state_dict(st["net"])
    opt.load_state_dict(st["opt"])
    sched.last_epoch = st["sched_epoch"]
    rng.bit_generator.state = st["rng"]  # training's only generator (older states also hold torch's: not used)
    return int(st["step"])
