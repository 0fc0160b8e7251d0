"""Adapting a trained detector to a line from good parts only: what depends on the line is re-estimated, the
decision threshold is set from good parts that the fitting never saw.

What depends on the line, in this model:
  - the input normalisation (``Normalizer``: per-channel mean and std over all pixels of the region of interest,
    the same statistic training used): exposure, gain, light and belt move it;
  - per-position statistics: the variation model's appearance (mean, principal components, per-pixel scales;
    ``model.draem.variation``), when the detector has one: re-estimated on the line's good parts, registered to the
    reference it was trained with (its part region kept; with blurred copies of the parts when the model was fitted
    with them, ``VariationModel.blur_copies_sigma``; the frame around each part read by the registration, as the
    station reads it, when the model reads it: ``ModelConfig.around_px``, kept in the adapted file); its second look,
    when it has one, on the line's own good parts as references (``model.draem.second_look``); then the second look's
    gate and both detectors' calibration, from the held-out scores; its shape check, when the model has one
    (``model.draem.shape_check``): the edge from the refit's reference, the good parts' sag spread from all of them,
    its threshold the largest z of a held-out part against the parts fitted without it, the window's 1 % point from
    the held-out parts; and its outline check (``model.draem.outline_check``) alike. Each check's threshold is then
    floored at the trained model's (``AdaptConfig.floor_checks``, on by default): the largest z of n good parts lets
    about 1/(n + 1) of new good parts beyond it, and the trained one, in the same units (robust z against the parts'
    own spread), was set on the model's good calibration parts (363 for the shipped file), so on fewer parts it is the
    better estimate of the good parts' tail. Measured on fresh seed 1203 (docs/results/2026-12-05-adapt-floor.md):
    adapted on 90 good parts the shipped file rejected 9 of 206 others without the floor (7 by the outline check's
    bottom edge, refitted at z 5.23 against the trained 8.68) and 2 with it; on 200, 8 and 5; defective parts caught
    65.8 % both ways on 90, 73.8 % and 73.3 % on 200;
  - whether the networks still judge: their held-out good parts' median image score, in robust standard
    deviations of their good validation parts (the trained calibration), after the refit; above
    ``DOMAIN_SHIFT_SD`` they are out of their domain on this line and the adapted model decides on the variation
    model alone (``ModelConfig.decision``; ``AdaptConfig.keep_networks`` keeps them);
  - optionally the weights: a brief fine-tune on the good parts with DRAEM's synthetic anomalies
    (``AdaptConfig.fine_tune_steps``; off by default).

Threshold rule (``adapted_threshold``): reject at most ``false_reject`` of good parts. Held-out scores come
from cross-fitting when only the normalisation is refitted (``folds`` folds: each part is scored by a normaliser
fitted on the other folds, so every good part is held out once and N parts give N held-out scores); with
fine-tuning a fixed share (``holdout_fraction``) is held out of both the normaliser and the fine-tune. The
threshold is the larger of the empirical quantile (no more than the allowed number of held-out parts at or above
it) and a logit-normal tail fit at 1 - ``false_reject``: with 50 parts a 1 % target lies beyond the largest
score, which the tail fit extrapolates instead of trusting the maximum.

Plain torch and numpy: this module reads no files (the caller loads the good parts' priors).
"""

from __future__ import annotations

import copy
import logging
import math
from dataclasses import asdict, dataclass, field, replace
from statistics import NormalDist
from typing import Any

import numpy as np
import torch

from .anomaly import AnomalyConfig, synthesize
from .config import GOOD_REJECTED_RATE
from .detector import Detector
from .errors import ModelError
from .loss import draem_loss
from .metrics import false_reject_threshold, usable_threshold
from .networks import DraemTrainOutput
from .preprocess import Normalizer
from .residual import NO_BLEND, NO_LOOK
from .second_look import MIN_REFERENCES
from .shape_check import ShapeCheck
from .variation import VariationModel, combined_score
from .with_variation import (
    blend_inputs,
    edge_sags,
    look_scores,
    member_scores,
    outline_deviations,
    residual_raw,
    rows,
    second_look_scores,
    shape_window,
)

log = logging.getLogger(__name__)

MIN_GOOD = 10
"""Fewer good parts than this cannot set a threshold worth the name."""
RECOMMENDED_GOOD = 200
"""Good parts to adapt a model with the variation member on; fewer work, with a note. The refit keeps one
appearance component per 20 parts (``variation.COMPONENTS``): 50 parts keep 1-2. On renders of a line with its
camera, stray light and exposure fixed but the parts' material and pose varying, the shipped model scored image
AUROC 0.924 unadapted, 0.889 adapted on 50 good parts, 0.912 on 100 and 0.925 on 210; with the parts uniform and
the station varying, 0.861, 0.830, 0.846 and 0.852. Only with both fixed did 50 help (0.878 -> 0.906;
docs/results/2026-11-25-narrow-lines.md). On fresh seed 1203 (the shipped line as built) the shipped file caught
65.8 % of defective parts adapted on 90 good parts, 73.3 % on 200 and 70.1 % unadapted
(docs/results/2026-12-05-adapt-floor.md)."""
PER_POSITION = "none (the detector keeps no per-position statistics of the part)"
PER_POSITION_REFIT = "the variation model's appearance and the calibration, re-estimated on the good parts"
DOMAIN_SHIFT_SD = 3.0
"""Networks whose good parts score further than this above their good validation parts (robust SD), after the
refit, are out of their domain on the line. Measured (docs/results/2026-11-24-low-rank-variation.md): on their own
line rendered at 8 instead of 16 spp the shipped networks' good parts sat 6.4 SD above, on a shifted line 8.1, on
held-out 16-spp renders of their line -0.5; the refitted variation model -0.4 and -0.5. Their findings on such a
line are mostly the shift: adapted, the shifted line scored image AUROC 0.54 by the networks, 0.76 by the variation
model, 0.71 by the two combined."""


@dataclass(frozen=True)
class AdaptConfig:
    """false_reject: share of good parts the threshold may reject; folds: cross-fitting folds (normalisation
    only); fine_tune_steps: 0 = no fine-tune; holdout_fraction: good parts kept out of a fine-tune for the
    threshold; refit_normalizer: False keeps the trained normaliser (threshold only); keep_networks: keep the
    networks in the decision even when they are out of their domain; floor_checks: the refitted shape and outline
    checks' thresholds no lower than the trained model's (module docstring)."""

    false_reject: float = GOOD_REJECTED_RATE
    keep_networks: bool = False
    folds: int = 5
    fine_tune_steps: int = 0
    fine_tune_lr: float = 2e-5
    batch_size: int = 8
    holdout_fraction: float = 0.3
    refit_normalizer: bool = True
    floor_checks: bool = True
    seed: int = 0
    anomaly: AnomalyConfig = field(default_factory=AnomalyConfig)

    def __post_init__(self) -> None:
        if not 0.0 < self.false_reject < 0.5:
            raise ModelError(f"false_reject {self.false_reject}: a share in (0, 0.5)")
        if self.folds < 2:
            raise ModelError(f"folds {self.folds}: at least 2")
        if not 0.0 < self.holdout_fraction < 1.0:
            raise ModelError(f"holdout_fraction {self.holdout_fraction}: a share in (0, 1)")
        if self.fine_tune_steps < 0:
            raise ModelError(f"fine_tune_steps {self.fine_tune_steps}: >= 0")


@dataclass(frozen=True)
class Held:
    """Good parts held out of a fit: ``detector`` fitted without them, their (N, C, S, S) priors ``x`` and the frame
    around each (``Detector.predict``'s ``around``), or None when the model reads the view alone."""

    detector: Detector
    x: torch.Tensor
    around: torch.Tensor | None = None

    def take(self, index: torch.Tensor) -> Held:
        """The same detector with parts ``index`` of these."""
        return Held(self.detector, self.x[index], None if self.around is None else self.around[index])


@dataclass(frozen=True)
class ThresholdChoice:
    """threshold and how: ``empirical`` (quantile of the held-out scores) and ``tail`` (logit-normal fit)."""

    threshold: float
    rule: str
    empirical: float
    tail: float


@dataclass
class AdaptResult:
    """What adaptation changed and what the threshold does on the held-out good parts."""

    normalizer_before: Normalizer
    normalizer_after: Normalizer
    threshold: ThresholdChoice
    heldout_scores: np.ndarray
    heldout_false_reject: float
    n_good: int
    n_heldout: int
    scheme: str
    fine_tune_steps: int = 0
    per_position: str = PER_POSITION
    networks_shift_sd: float | None = None
    decision: str = "combined"
    decision_changed: bool = False
    """True when the domain check moved the decision from combined to the variation model alone."""
    advice: str | None = None
    """What the user should know about this adaptation (fewer good parts than ``RECOMMENDED_GOOD``), or None."""
    shape: str | None = None
    """The shape check of the adapted model (``_refit_shape``): what it measures, or why it has none; None when the
    model had none to adapt."""

    def record(self) -> dict[str, Any]:
        """JSON-able summary for the model's sidecar."""
        s = self.heldout_scores
        return {"n_good": self.n_good, "n_heldout": self.n_heldout, "scheme": self.scheme,
                "threshold": self.threshold.threshold, "threshold_rule": self.threshold.rule,
                "heldout_false_reject": self.heldout_false_reject,
                "n_heldout_rejected": int((s > self.threshold.threshold).sum()),
                "heldout_scores": {"median": float(np.median(s)), "p95": float(np.percentile(s, 95)),
                                   "max": float(s.max())},
                "normalization_before": asdict(self.normalizer_before),
                "normalization_after": asdict(self.normalizer_after),
                "fine_tune_steps": self.fine_tune_steps, "per_position": self.per_position,
                "networks_shift_sd": self.networks_shift_sd, "decision": self.decision,
                "decision_changed": self.decision_changed, "advice": self.advice, "shape": self.shape}


def adapted_threshold(scores: np.ndarray, false_reject: float) -> ThresholdChoice:
    """The threshold that rejects at most ``false_reject`` of good parts with these held-out ``scores`` (module
    docstring): max of the empirical bound and the logit-normal tail quantile."""
    s = np.sort(np.asarray(scores, dtype=np.float64).reshape(-1))
    if s.size == 0 or not np.all(np.isfinite(s)):
        raise ModelError("adapted_threshold needs finite held-out scores")
    empirical = float(np.nextafter(false_reject_threshold(s, false_reject), np.inf))
    z = np.log(np.clip(s, 1e-6, 1 - 1e-6)) - np.log1p(-np.clip(s, 1e-6, 1 - 1e-6))
    q = float(z.mean() + NormalDist().inv_cdf(1 - false_reject) * z.std(ddof=1)) if s.size > 1 else float(z[0])
    tail = float(1.0 / (1.0 + math.exp(-q)))
    t = usable_threshold(max(empirical, tail), "adapt")
    which = "logit-normal tail" if tail > empirical else "empirical quantile"
    rule = (f"adapt: at most {false_reject:.2%} of {s.size} held-out good parts rejected ({which}; empirical "
            f"{empirical:.4g}, tail {tail:.4g})")
    return ThresholdChoice(t, rule, empirical, tail)


def with_normalizer(detector: Detector, normalizer: Normalizer) -> Detector:
    """A copy of ``detector`` (eval mode) with another input normaliser."""
    d = copy.deepcopy(detector)
    d.normalizer = normalizer
    return d.eval()


@torch.no_grad()
def image_scores(detector: Detector, x: torch.Tensor, batch_size: int = 16, around: torch.Tensor | None = None
                 ) -> np.ndarray:
    """(N,) image scores of (N, C, S, S) priors (roi "center"/"frame": scored over the whole square); ``around``: the
    frame around each view (``Detector.predict``)."""
    detector.eval()
    out = [detector.predict(x[i:i + batch_size], around=rows(around, i, batch_size)).score.float().cpu()
           for i in range(0, x.shape[0], batch_size)]
    return torch.cat(out).numpy()


def _refit(detector: Detector, x: torch.Tensor, cfg: AdaptConfig, around: torch.Tensor | None = None) -> Detector:
    """A copy with the normalisation (and the variation model's statistics, when it has one) fitted on ``x`` (the
    frame ``around`` each read by the registration, when given)."""
    d = with_normalizer(detector, _fit(detector, x, cfg))
    if d.variation is not None:
        looked = d.variation.second_look.references > 0
        references = d.variation.fit(x, keep_reference=True, around=around)  # a new fit has no second look
        if looked and len(references) >= MIN_REFERENCES:  # one on the line's own parts, calibrated held out
            d.variation.second_look.fit(references, d.variation.region.numpy())
    return d


def _held_out(detector: Detector, good: Held, cfg: AdaptConfig, fit: np.ndarray, held: np.ndarray) -> Held:
    """Parts ``held`` of ``good``, with ``detector`` refitted on its parts ``fit`` (``_refit``)."""
    fitted = good.take(torch.from_numpy(fit))
    return replace(good.take(torch.from_numpy(held)), detector=_refit(detector, fitted.x, cfg, fitted.around))


def _heldout_scores(final: Detector, parts: list[Held], keep_networks: bool) -> tuple[np.ndarray, float | None]:
    """Held-out image scores: each ``Held`` scored by its detector. With a variation model, the
    networks' shift is measured against the trained calibration (``DOMAIN_SHIFT_SD``: beyond it, and unless
    ``keep_networks``, ``final`` decides on the variation model alone), then the final detector's calibration is
    set from all held-out member scores, and every part's combined score uses it (a calibration from the fitted
    parts would be biased low). With residual networks deciding, their calibration is set the same way from their
    held-out raw scores and the parts' scores are the detector's own (the decision stays theirs: the networks'
    shift concerns the DRAEM networks only). Returns (scores, the networks' shift in robust SD or None)."""
    if final.variation is None:
        return np.concatenate([image_scores(p.detector, p.x, around=p.around) for p in parts]), None
    _calibrate_second_look(final, parts)
    _calibrate_look(final, parts)
    _calibrate_blend(final, parts)
    pairs = [member_scores(p.detector, p.x, around=p.around) for p in parts]
    net, var = torch.cat([p[0] for p in pairs]), torch.cat([p[1] for p in pairs])
    location, spread = (float(c) for c in final.variation.calibration[:2])
    shift = (float(net.double().median()) - location) / spread
    final.variation.calibrate(net, var)
    if final.residual is not None and final.config.decision == "residual":  # they decide: calibrate them the same way
        raw = torch.cat([residual_raw(p.detector, p.x, around=p.around) for p in parts], 1)
        final.residual.calibrate(raw)
        for p in parts:
            assert p.detector.residual is not None
            p.detector.residual.calibration.copy_(final.residual.calibration)
        return np.concatenate([image_scores(p.detector, p.x, around=p.around) for p in parts]), shift
    if shift > DOMAIN_SHIFT_SD and not keep_networks:
        final.config = final.config.with_(decision="variation")
    return combined_score(net, var, final.variation.calibration, final.config.networks_decide).numpy(), shift


def _refit_shape(final: Detector, good: Held, parts: list[Held], splits: list[tuple[np.ndarray, np.ndarray]],
                 batch_size: int = 16, outline: bool = False, floor: VariationModel | None = None) -> str:
    """The shape check of ``final`` (refit on the good parts ``good``, its detector unused) again, in place (module
    docstring): its edge from the refit's reference, its calibration cross-fitted over ``splits``
    (``ShapeCheck.calibrate_crossed``), the window's 1 % point from ``parts`` (each fold's detector and its held
    parts). What it measures; when the refit
    shows no straight bottom edge or too few parts show it, why it has none (a warning: the model is then judged
    without it). ``outline``: the model had an outline check, which is refitted alike (``_refit_outline``), or
    switched off with the shape check. ``floor``: the trained variation model, whose checks' thresholds the refitted
    ones are floored at (``AdaptConfig.floor_checks``)."""
    var = final.variation
    assert var is not None
    window = shape_window([(p.detector.variation, p.x, p.around) for p in parts if p.detector.variation is not None],
                          batch_size)
    try:
        if not var.shape.find(var.reference.numpy(), var.region.numpy()):
            raise ModelError("the refit's reference shows no straight bottom edge")
        var.shape.calibrate_crossed(edge_sags(var, good.x, good.around), splits, window)
    except ModelError as exc:
        var.shape = ShapeCheck()  # off: no edge, no calibration
        var.outline.clear()  # fitted beside it (``station shape``): off with it
        why = f"no shape check: {exc} (a bent part is judged by the window alone)"
        if outline:
            why += "; no outline check with it (a step along an edge too)"
        log.warning("the adapted variation model has %s", why)
        return why
    first, end = (int(v) for v in var.shape.edge[:2])
    spread = float(var.shape.calibration[1])
    whose = _floored(var.shape.calibration, 2, None if floor is None else floor.shape.calibration)
    said = (f"shape check refitted: the bottom edge over input columns {first}-{end - 1}, good parts' sag spread "
            f"{spread:.3g} px, threshold z {whose}")
    return f"{said}; {_refit_outline(var, good.x, splits, window, floor, good.around)}" if outline else said


def _floored(calibration: torch.Tensor, k: int, trained: torch.Tensor | None) -> str:
    """Floor the refitted threshold ``calibration[k]`` at the trained model's ``trained[k]`` (when given and
    finite), in place; says which it is: "z 5.20 (the largest held-out part's)" or "z 5.20 (the trained model's;
    the largest held-out part's 3.10)"."""
    refit = float(calibration[k])
    floor = math.nan if trained is None else float(trained[k])
    if not floor > refit:  # no floor, or the refit's is the higher
        return f"{refit:.2f} (the largest held-out part's)"
    calibration[k] = floor
    return f"{floor:.2f} (the trained model's; the largest held-out part's {refit:.2f})"


def _refit_outline(var: VariationModel, x: torch.Tensor, splits: list[tuple[np.ndarray, np.ndarray]],
                   window: float, floor: VariationModel | None = None, around: torch.Tensor | None = None) -> str:
    """The outline check (``model.draem.outline_check``) of ``var`` again, in place, as ``_refit_shape`` refits the
    shape check: its edges from the refit's reference and region, its statistics and thresholds cross-fitted over
    ``splits`` of the good parts ``x`` (and the frame ``around`` each, or None), each edge's threshold floored at
    ``floor``'s (the trained variation model), when given. What it measures, or why it has none (a warning)."""
    try:
        if not var.outline.find(var.reference.numpy(), var.region.numpy()):
            raise ModelError("the refit's reference shows no two straight edges along the part")
        var.outline.calibrate_crossed(outline_deviations(var, x, around), splits, window)
    except ModelError as exc:
        var.outline.clear()
        why = f"no outline check: {exc} (a step along an edge is judged by the window alone)"
        log.warning("the adapted variation model has %s", why)
        return why
    trained = None if floor is None else floor.outline.calibration
    bottom, top = (_floored(var.outline.calibration, k, trained) for k in (0, 1))
    return f"outline check refitted: thresholds z {bottom} at the bottom edge and z {top} at the top edge"


def _calibrate_look(final: Detector, parts: list[Held]) -> None:
    """The residual networks' look (``model.draem.residual``), when they are the second look, from the held-out
    parts' top logits and variation scores, each scored by the detector fitted without them (after its second look
    is calibrated), then shared by all of them; the networks themselves are kept. ``final`` looks no more (the
    networks only report) when the second look was dropped."""
    if final.residual is None or not final.residual.looks:
        return
    if final.variation is None or not final.variation.second_look.references:
        for d in (final, *(p.detector for p in parts)):
            assert d.residual is not None
            d.residual.look.copy_(torch.tensor(NO_LOOK, dtype=torch.float64))
        return
    pairs = [look_scores(p.detector, p.x, around=p.around) for p in parts]
    final.residual.calibrate_look(torch.cat([p[0] for p in pairs]), np.concatenate([p[1] for p in pairs]))
    for p in parts:
        assert p.detector.residual is not None
        p.detector.residual.look.copy_(final.residual.look)


def _calibrate_blend(final: Detector, parts: list[Held]) -> None:
    """The look's blend (``model.draem.residual.blended``), when it has one: its weight kept, its two thresholds from
    the held-out parts' scores and findings (``blend_inputs``), each scored by the detector fitted without them
    (after its look is calibrated), then shared by all of them. No blend when the look was dropped."""
    if final.residual is None or not float(final.residual.blend[0]) > 0:
        return
    detectors = (final, *(p.detector for p in parts))
    if not final.residual.looks:
        for d in detectors:
            assert d.residual is not None
            d.residual.blend.copy_(torch.tensor(NO_BLEND, dtype=torch.float64))
        return
    pairs = [blend_inputs(p.detector, p.x, around=p.around) for p in parts]
    final.residual.calibrate_blend(float(final.residual.blend[0]), np.concatenate([p[0] for p in pairs]),
                                   np.concatenate([p[1] for p in pairs]))
    for p in parts:
        assert p.detector.residual is not None
        p.detector.residual.blend.copy_(final.residual.blend)


def _calibrate_second_look(final: Detector, parts: list[Held]) -> None:
    """The refitted second look's gate and units (``model.draem.second_look``) from the held-out parts' window and
    test scores, each scored by the detector fitted without them, then shared by all of them; ``final`` keeps none
    when a fold's detector has none (too few parts to fit it)."""
    assert final.variation is not None
    if not final.variation.second_look.references:
        return
    if not all(p.detector.variation is not None and p.detector.variation.second_look.references for p in parts):
        final.variation.second_look.resize(0, 0)
        return
    scores = [second_look_scores(p.detector.variation, p.x, around=p.around) for p in parts
              if p.detector.variation is not None]
    final.variation.second_look.calibrate(np.concatenate([w for w, _ in scores]),
                                          np.concatenate([t for _, t in scores]))
    for p in parts:
        assert p.detector.variation is not None
        p.detector.variation.second_look.calibration.copy_(final.variation.second_look.calibration)


def fine_tune(detector: Detector, x: torch.Tensor, object_mask: torch.Tensor, steps: int, lr: float,
              batch_size: int, seed: int, anomaly: AnomalyConfig, progress: bool = True) -> Detector:
    """A copy of ``detector`` trained ``steps`` more steps on good parts ``x`` with synthetic anomalies (DRAEM's
    loss), at learning rate ``lr``; its normaliser is kept."""
    from tqdm import tqdm

    d = copy.deepcopy(detector).train()
    opt = torch.optim.Adam(d.parameters(), lr=lr)
    g_idx = torch.Generator().manual_seed(seed)
    g_syn = torch.Generator().manual_seed(seed + 7)
    for _ in tqdm(range(steps), desc="fine-tune", unit="step", disable=not progress, dynamic_ncols=True):
        idx = torch.randint(x.shape[0], (batch_size,), generator=g_idx)
        xb, ob = x[idx], object_mask[idx].bool()
        syn = synthesize(xb, d.config.priors, g_syn, anomaly, ob)
        clean, aug = d.normalize(xb), d.normalize(syn.augmented)
        total = torch.zeros(())
        for name, net in d.members.items():
            sl = d.member_slice(name)
            o = net(aug[:, sl])
            assert isinstance(o, DraemTrainOutput)
            total = total + draem_loss(clean[:, sl], o.reconstruction, o.logits, syn.mask).total
        opt.zero_grad(set_to_none=True)
        total.backward()
        opt.step()
        loss = float(total.detach())
        if not math.isfinite(loss):
            raise ModelError(f"fine-tune diverged: loss {loss}")
    return d.eval()


def _fit(detector: Detector, x: torch.Tensor, cfg: AdaptConfig) -> Normalizer:
    return Normalizer.fit(x) if cfg.refit_normalizer else detector.normalizer


def adapt(detector: Detector, x: torch.Tensor, object_mask: torch.Tensor, cfg: AdaptConfig = AdaptConfig(),
          progress: bool = True, around: torch.Tensor | None = None) -> tuple[Detector, AdaptResult]:
    """Adapt ``detector`` to the good parts ``x`` (N, C, S, S) at its input size (module docstring); returns the
    adapted copy (threshold not set on it: see ``AdaptResult.threshold``) and what was done. ``around``: (N, C,
    S + 2 a, ...) the frame around each part (``ModelConfig.around_px`` a; ``model.draem.roi.around_box``), read by
    the refit, its held-out scores and the checks' calibration as the station reads it, and the adapted file keeps
    ``around_px``; None (or a file that reads the view alone): all read the view alone, and so does the adapted
    file (``around_px`` 0: a refit on the view alone, read with the frame around, can reject every good part)."""
    n = x.shape[0]
    if n < MIN_GOOD:
        raise ModelError(f"adapting needs at least {MIN_GOOD} good parts, got {n}")
    if detector.config.roi == "object":
        raise ModelError("a model with roi 'object' needs ground-truth object masks at inference: not adaptable "
                         "to a line")
    a = detector.config.around_px
    if a == 0 or detector.variation is None:
        around = None
    elif around is not None and (around.shape[0] != n or tuple(around.shape[-2:]) != (x.shape[-2] + 2 * a,
                                                                                       x.shape[-1] + 2 * a)):
        raise ModelError(f"the frame around the parts is {tuple(around.shape)}: the model reads {a} input px around "
                         f"each of {n} views of {tuple(x.shape[-2:])}")
    good = Held(detector, x, around)
    order = torch.from_numpy(np.random.default_rng(cfg.seed).permutation(n))
    before = detector.normalizer
    what = "normalisation" + (" and variation statistics" if detector.variation is not None else "")
    if cfg.fine_tune_steps == 0:
        folds = min(cfg.folds, n)
        splits = [(np.setdiff1d(order.numpy(), order[k::folds].numpy()), order[k::folds].numpy())
                  for k in range(folds)]
        parts = [_held_out(detector, good, cfg, fit, held) for fit, held in splits]
        final = _refit(detector, x, cfg, around)
        heldout = np.empty(n)
        heldout[np.concatenate([held for _, held in splits])], shift = _heldout_scores(final, parts, cfg.keep_networks)
        scheme = f"cross-fitted {what}, {folds} folds"
        n_held, steps = n, 0
    else:
        n_held = max(1, round(cfg.holdout_fraction * n))
        held, fit = order[:n_held], order[n_held:]
        fitted = good.take(fit)
        tuned = _refit(detector, fitted.x, cfg, fitted.around)
        final = fine_tune(tuned, x[fit], object_mask[fit], cfg.fine_tune_steps, cfg.fine_tune_lr, cfg.batch_size,
                          cfg.seed, cfg.anomaly, progress)
        parts = [replace(good.take(held), detector=final)]
        splits = [(fit.numpy(), held.numpy())]
        heldout, shift = _heldout_scores(final, parts, cfg.keep_networks)
        scheme = f"{what} and {cfg.fine_tune_steps}-step fine-tune on {n - n_held}, {n_held} held out"
        steps = cfg.fine_tune_steps
    choice = adapted_threshold(heldout, cfg.false_reject)
    fr = float((heldout > choice.threshold).mean())  # rejected as the station rejects: score > threshold
    log.info("adapted on %d good parts (%s): threshold %.4g, %.1f %% of held-out good parts rejected", n, scheme,
             choice.threshold, 100 * fr)
    if (detector.variation is not None and detector.variation.second_look.references and final.variation is not None
            and not final.variation.second_look.references):
        log.warning("the adapted variation model has no second look (model.draem.second_look): it needs at least "
                    "%d good parts in each fold's fit", MIN_REFERENCES)
    shape = None
    if detector.variation is not None and detector.variation.shape.fitted:  # a refit's check is its own
        shape = _refit_shape(final, good, parts, splits, outline=detector.variation.outline.fitted,
                             floor=detector.variation if cfg.floor_checks else None)
    per_position = PER_POSITION if final.variation is None else PER_POSITION_REFIT
    changed = detector.config.decision != final.config.decision
    if changed:
        log.warning("the networks' good parts score %.1f robust SD above their validation parts on this line (limit "
                    "%.0f): out of their domain; the adapted model decides on the variation model alone", shift,
                    DOMAIN_SHIFT_SD)
    advice = None
    if final.variation is not None and n < RECOMMENDED_GOOD:
        advice = (f"{n} good parts, fewer than the {RECOMMENDED_GOOD} recommended: the variation model's refit keeps "
                  "few appearance components, and on renders of lines where something still varied 50 parts scored "
                  "below the model unadapted; adapt again on more good parts")
        log.warning(advice)
    # the adapted file reads what its refit and threshold read (ModelConfig.around_px)
    final.config = final.config.with_(around_px=a if around is not None else 0)
    return final, AdaptResult(before, final.normalizer, choice, heldout, fr, n, n_held, scheme, steps, per_position,
                              shift, final.config.decision, changed, advice, shape)
