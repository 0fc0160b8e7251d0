"""A trained detector plus the registered variation model (``model.draem.variation``): fitted on good training
parts, calibrated on good validation parts, networks and normalisation copied unchanged; and plus the residual
networks that read it (``model.draem.residual``)."""

from __future__ import annotations

import copy
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path

import numpy as np
import torch

from .config import Alignment, channel_slices
from .detector import Detector
from .errors import ModelError
from .lens_copies import LensCopies, lensed_signed
from .metrics import false_reject_threshold
from .residual import train_member
from .roi import around_px_of
from .second_look import MIN_REFERENCES
from .variation import VariationModel, network_score, per_part


@torch.no_grad()
def add_variation(detector: Detector, good: torch.Tensor, good_object_mask: torch.Tensor | None,
                  val_good: torch.Tensor, batch: int = 16, decision: str = "combined",
                  blur_copies_sigma: float = 0.0,
                  global_polarization: Alignment | str | bool = Alignment.OFF,
                  clusters: int = 0, global_contrast: Alignment | str = Alignment.OFF,
                  second_look: bool = False, curvature_sigma: float = 0.0, second_look_test: bool = True,
                  judged_priors: Sequence[str] | None = None, smooth_field: bool = False) -> Detector:
    """A copy of ``detector`` with ``config.variation`` set: the variation model fitted on ``good`` (N, C, H, W)
    physical priors of good training parts (``good_object_mask`` (N, H, W): where the part is; None: the whole
    input), then calibrated with both detectors' image scores on ``val_good`` (good validation parts, never the
    training parts: a fitted model scores its own parts low). ``decision``: ``ModelConfig.decision`` of the copy
    (which finding rejects; calibration and member scores do not depend on it). ``blur_copies_sigma``: the fit also
    sees blurred copies of the good parts (``VariationModel.fit``; 0: none). ``global_polarization``: how each
    frame's polarization is put onto the good parts' by one frame-wide gain and turn (``Alignment``,
    ``VariationModel.fit``). ``clusters``: how many groups of good parts, by appearance, each part is judged within
    (``VariationModel.fit``; 0: none). ``global_contrast``: how each frame's contrast is put onto the good
    parts' (``Alignment``, ``VariationModel.fit``). ``second_look``: keep the good parts' left-out residuals as
    references for a second look at suspicious parts (``add_second_look``), when there are at least
    ``MIN_REFERENCES`` of them (fewer: none). ``curvature_sigma``: the window statistic (``VariationModel.fit``; 0:
    the box). ``second_look_test``: the second look tests the regions its map points at (False: it only gates the
    parts a look network is asked about; ``model.draem.second_look``). ``judged_priors``: the priors whose channels
    the window statistic is taken over (``judged_channels``; None: all; the others are read, intensity registers the
    part); ModelError for a prior the detector does not read. ``smooth_field``: take a lens's smooth field out of
    every frame's residual (``VariationModel.fit``)."""
    if detector.config.variation:
        raise ModelError("the detector already has a variation model")
    if len(val_good) < 2:
        raise ModelError(f"calibrating the variation model needs good validation parts, got {len(val_good)}")
    around = around_px_of(detector.config.roi, detector.config.priors, True)  # the frame around the view: read
    out = Detector(detector.config.with_(variation=True, decision=decision, around_px=around), detector.normalizer)
    missing, unexpected = out.load_state_dict(detector.state_dict(), strict=False)
    assert not unexpected and all(k.startswith("variation.") for k in missing), (missing, unexpected)
    out.eval()
    assert out.variation is not None
    references = out.variation.fit(good, good_object_mask, blur_copies_sigma=blur_copies_sigma,
                                   global_polarization=global_polarization, clusters=clusters,
                                   global_contrast=global_contrast, curvature_sigma=curvature_sigma,
                                   judged_channels=judged_channels(detector.config.priors, judged_priors),
                                   smooth_field=smooth_field)
    if second_look and len(references) >= MIN_REFERENCES:
        add_second_look(out, references, val_good, batch, test=second_look_test)
    out.variation.calibrate(*member_scores(out, val_good, batch))  # member scores do not depend on calibration
    out.variation.check()
    return out


SHAPE_WINDOW_RATE = 0.01
"""The shape check's finding is scaled to the window score at this share of good validation parts rejected."""


def rows(around: torch.Tensor | None, i: int, n: int) -> torch.Tensor | None:
    """Rows ``i`` to ``i + n`` of ``around`` (the frame around each of a batch's views), or None without one."""
    return None if around is None else around[i:i + n]


@torch.no_grad()
def shape_window(scored: Sequence[tuple[VariationModel, torch.Tensor, torch.Tensor | None]], batch: int = 16
                 ) -> float:
    """The window score at ``SHAPE_WINDOW_RATE`` of good parts, each set of (N, C, H, W) priors in ``scored`` (with
    the frame around each, or None: ``VariationModel.zmaps``'s ``around``) scored by its variation model (``zmaps``,
    in batches; before a shape check scores: its own window)."""
    window = [var.zmaps(x[i:i + batch], around=rows(a, i, batch)).scores.numpy() for var, x, a in scored
              for i in range(0, len(x), batch)]
    return false_reject_threshold(np.concatenate(window), SHAPE_WINDOW_RATE)


def edge_sags(var: VariationModel, x: torch.Tensor, around: torch.Tensor | None = None) -> np.ndarray:
    """(N,) the shape check's sag of each of (N, C, H, W) priors (and the frame around each, or None;
    ``VariationModel.edge_sag``; NaN where unseen)."""
    return np.array([var.edge_sag(xi, a) for xi, a in zip(x.float().cpu().numpy(), per_part(around, len(x)),
                                                           strict=True)])


def outline_deviations(var: VariationModel, x: torch.Tensor, around: torch.Tensor | None = None) -> np.ndarray:
    """(N, 2, W) the outline check's deviations of each of (N, C, H, W) priors (and the frame around each, or None;
    ``VariationModel.outline_deviations``)."""
    return np.stack([var.outline_deviations(xi, a) for xi, a in zip(x.float().cpu().numpy(), per_part(around, len(x)),
                                                                    strict=True)])


@torch.no_grad()
def add_shape_check(detector: Detector, good: torch.Tensor, val_good: torch.Tensor, batch: int = 16) -> bool:
    """Give ``detector``'s variation model its shape check (``model.draem.shape_check``), in place: the edge from its
    reference and region, the sag's median and spread from ``good`` (N, C, H, W) good training parts' physical priors,
    its threshold from ``val_good``'s (good validation parts), with the window score at ``SHAPE_WINDOW_RATE`` of
    them. False, and no check, when the region shows no straight bottom edge; ModelError as
    ``ShapeCheck.calibrate``."""
    var = detector.variation
    if var is None:
        raise ModelError("the shape check reads the variation model's registration: add the variation model first")
    if not var.shape.find(var.reference.numpy(), var.region.numpy()):
        return False
    var.shape.calibrate(edge_sags(var, good), edge_sags(var, val_good), shape_window([(var, val_good, None)], batch))
    var.check()
    return True


@torch.no_grad()
def add_outline_check(detector: Detector, good: torch.Tensor, val_good: torch.Tensor,
                      window: float | None = None, batch: int = 16) -> str | None:
    """Give ``detector``'s variation model its outline check (``model.draem.outline_check``), in place: the edges from
    its reference and region, the per-column statistics from ``good`` (N, C, H, W) good training parts' physical
    priors, the thresholds from ``val_good``'s (good validation parts), with ``window`` the window score at
    ``SHAPE_WINDOW_RATE`` of them (None: measured here; the shape check's, when fitted on the same parts, is the
    same number). None when fitted; else why not, and the check is off (no two straight edges along the part, too
    few parts showing them)."""
    var = detector.variation
    if var is None:
        raise ModelError("the outline check reads the variation model's registration: add the variation model first")
    if not var.outline.find(var.reference.numpy(), var.region.numpy()):
        return "the reference shows no two straight edges along the part"
    try:
        var.outline.calibrate(outline_deviations(var, good), outline_deviations(var, val_good),
                              shape_window([(var, val_good, None)], batch) if window is None else window)
    except ModelError as exc:
        var.outline.clear()
        return str(exc)
    var.check()
    return None


def judged_channels(priors: Sequence[str], judged_priors: Sequence[str] | None) -> list[int] | None:
    """The channel indices of ``judged_priors`` in a detector reading ``priors`` (``config.channel_slices``; None:
    None, every channel). ModelError for a prior it does not read, or none."""
    if judged_priors is None:
        return None
    slices = channel_slices(tuple(priors))
    unknown = [p for p in judged_priors if p not in slices]
    if unknown or not judged_priors:
        raise ModelError(f"judged priors {list(judged_priors)}: the model reads {', '.join(priors)}; name one or "
                         f"more of them")
    return sorted({c for p in judged_priors for c in range(slices[p].start, slices[p].stop)})


@torch.no_grad()
def add_second_look(detector: Detector, references: np.ndarray, val_good: torch.Tensor, batch: int = 16,
                    test: bool = True) -> None:
    """Give ``detector``'s variation model its second look (``model.draem.second_look``), in place: ``references``
    (R, C, H, W) the good training parts' left-out signed residuals (``VariationModel.fit``'s return), gate and units
    from ``val_good`` (N, C, H, W) good validation parts' window and test scores. ``test``: whether it tests the
    regions its map points at (``SecondLook.tests``; False: it only gates the parts a look network is asked about)."""
    assert detector.variation is not None
    var = detector.variation
    var.second_look.fit(references, var.region.numpy())
    var.second_look.tests.fill_(1.0 if test else 0.0)
    var.second_look.calibrate(*second_look_scores(var, val_good, batch))


@torch.no_grad()
def second_look_scores(var: VariationModel, x: torch.Tensor, batch: int = 16, around: torch.Tensor | None = None
                       ) -> tuple[np.ndarray, np.ndarray]:
    """(N,) window and (N,) test scores of parts ``x`` (N, C, H, W) (and the frame around each, or None) by ``var``'s
    second look, whose references are fitted and whose gate is not yet set (so no part is looked at again): what
    ``SecondLook.calibrate`` reads."""
    region = var.region.numpy()
    window, test = [], []
    for i in range(0, len(x), batch):
        o = var.zmaps(x[i:i + batch], signed=True, around=rows(around, i, batch))
        assert o.signed is not None and o.judged is not None
        window += o.scores.tolist()
        for m, s, j in zip(o.maps.numpy(), o.signed.numpy(), o.judged.numpy(), strict=True):
            test.append(var.second_look.test(m, (s ** 2).sum(0), j, region))
    return np.array(window), np.array(test)


def without_variation(detector: Detector) -> Detector:
    """A copy of ``detector`` without its variation model: the networks and the normalisation only (decision
    "combined"), for fitting the variation model again (``station variation --refit``). ModelError when it has
    residual networks: they read the fit being replaced."""
    if detector.residual is not None or detector.config.residual_members:
        raise ModelError("the detector has residual networks, which read its variation model: refit from the "
                         "checkpoint without them")
    return networks_only(detector)


def networks_only(detector: Detector) -> Detector:
    """A copy of ``detector`` with its networks and normalisation only (decision "combined"): its variation model
    and the residual networks that read it dropped. The source of a variation model fitted on another camera's
    parts (``scripts/make-side-model.sh``: the side camera's file from the shipped line file)."""
    out = Detector(detector.config.with_(variation=False, residual_members=0, decision="combined", around_px=0),
                   detector.normalizer)
    out.load_state_dict({k: v for k, v in detector.state_dict().items()
                         if not k.startswith(("variation.", "residual."))})
    return out.eval()


@torch.no_grad()
def member_scores(detector: Detector, x: torch.Tensor, batch_size: int = 16, around: torch.Tensor | None = None
                  ) -> tuple[torch.Tensor, torch.Tensor]:
    """(N,) network and (N,) variation image scores of a detector with a variation model, before combining; ``around``:
    the frame around each part (``Detector.predict``), or None."""
    detector.eval()
    net, var = [], []
    for i in range(0, x.shape[0], batch_size):
        out = detector.predict(x[i:i + batch_size], around=rows(around, i, batch_size))
        net.append(network_score(out.member_scores).float().cpu())
        var.append(out.member_scores["variation"].float().cpu())
    return torch.cat(net), torch.cat(var)


def can_look(detector: Detector) -> bool:
    """Whether residual networks can be ``detector``'s second look (``add_residual(look=True)``): its variation model
    decides, and has a fitted second look."""
    return (detector.variation is not None and detector.config.decision == "variation"
            and detector.variation.second_look.references > 0)


@torch.no_grad()
def add_residual(detector: Detector, good: torch.Tensor, good_object_mask: torch.Tensor | None,
                 defects: torch.Tensor, defect_masks: torch.Tensor, val_good: torch.Tensor, members: int = 3,
                 steps: int = 3000, seed: int = 0, progress: Callable[[str], None] | None = None,
                 look: bool = False, states: Path | None = None, lens: LensCopies | None = None) -> Detector:
    """A copy of ``detector`` (which has the variation model) with ``members`` residual networks
    (``model.draem.residual``) deciding: trained on the left-out residuals of ``good`` (N, C, H, W) good training
    parts (the variation model fitted again on them, in a copy: the same parts give the same fit, and the model's
    own, with its second look, is kept), ``defects`` (M, C, H, W) rendered defective training parts with
    ``defect_masks`` (M, H, W) registered as the frames, member k trained with seed ``seed + k``; both detectors
    then calibrated on ``val_good`` (good validation parts). ``look``: the networks do not decide but are the
    variation model's second look (``ResidualDetector.look``, calibrated on ``val_good``); the model's decision is
    kept, and it needs a fitted second look (``add_second_look``). ``progress``: one line per 250 steps. ``states``: a
    folder for each member's resume state (``member-K.pt``, ``train_member``'s ``state``): an interrupted run given
    the same folder continues where it stopped; the caller removes it when the detector is saved. ``lens``: a lens
    copy of each good part joins the good parts the networks learn from (``model.draem.lens_copies``)."""
    if detector.variation is None:
        raise ModelError("the residual networks read the variation model: add it first (station variation)")
    if detector.residual is not None:
        raise ModelError("the detector already has residual networks: start from the model they were added to")
    if len(val_good) < 2:
        raise ModelError(f"calibrating the residual networks needs good validation parts, got {len(val_good)}")
    if look and not can_look(detector):
        raise ModelError("the residual networks as a second look need a model decided by its variation model with "
                         "its second look (station variation --decision variation --second-look)")
    out = Detector(detector.config.with_(residual_members=members,
                                         decision=detector.config.decision if look else "residual"),
                   detector.normalizer)
    missing, unexpected = out.load_state_dict(detector.state_dict(), strict=False)
    assert not unexpected and all(k.startswith("residual.") for k in missing), (missing, unexpected)
    out.eval()
    assert out.variation is not None and out.residual is not None
    var, res = out.variation, out.residual
    signed = torch.from_numpy(copy.deepcopy(var).fit(good, good_object_mask))
    region = var.region.bool()
    good_in = res.inputs(signed, region, var.window_spread).numpy()
    if lens is not None:
        copies = res.inputs(lensed_signed(var, good, signed, lens), region, var.window_spread).numpy()
        good_in = np.concatenate([good_in, copies])
    if len(defects):
        v = var.zmaps(defects, signed=True)
        assert v.signed is not None and v.judged is not None
        masks = (var.register_masks(defects, defect_masks) & v.judged & region).numpy()
        defect_in = res.inputs(v.signed, region, var.window_spread).numpy()
    else:
        masks, defect_in = np.zeros((0, *region.shape), bool), good_in[:0]
    for k, net in enumerate(res.members):
        def report(step: int, loss: float, k: int = k) -> None:
            if progress is not None:
                progress(f"residual network {k + 1}/{members}: step {step + 1}/{steps}, loss {loss:.3f}")
        with torch.enable_grad():
            train_member(net, good_in, defect_in, masks, steps, seed + k, progress=report,
                         state=None if states is None else states / f"member-{k}.pt")
    var.calibrate(*member_scores(out, val_good))
    res.calibrate(residual_raw(out, val_good))
    if look:
        calibrate_look(out, val_good)
    var.check()
    res.check()
    return out


@torch.no_grad()
def look_scores(detector: Detector, x: torch.Tensor, batch_size: int = 16, around: torch.Tensor | None = None
                ) -> tuple[torch.Tensor, np.ndarray]:
    """What the residual networks' ``look`` is calibrated from, on parts ``x`` (N, C, H, W) (and the frame around
    each, or None): (N,) their mean top logits (``ResidualDetector.top_logits``) and (N,) the variation model's scores
    in the window's robust SD."""
    assert detector.variation is not None
    logits, scores = [], []
    for v_scores, top in _window_and_logits(detector, x, batch_size, around):
        logits.append(top)
        scores.append(detector.variation.second_look.window_sd(v_scores.double().numpy()))
    return torch.cat(logits), np.concatenate(scores)


def _window_and_logits(detector: Detector, x: torch.Tensor, batch_size: int, around: torch.Tensor | None
                       ) -> Iterator[tuple[torch.Tensor, torch.Tensor]]:
    """Per batch of parts ``x`` (N, C, H, W) (and the frame around each, or None): the variation model's scores (B,)
    with its checks and without the look, and the residual networks' mean top logits (B,) on its signed residuals."""
    assert detector.variation is not None and detector.residual is not None
    for i in range(0, len(x), batch_size):
        v = detector.variation.zmaps(x[i:i + batch_size], signed=True, around=rows(around, i, batch_size))
        assert v.signed is not None and v.judged is not None
        yield v.scores, detector.residual.top_logits(*detector.residual_inputs(v.signed, v.judged))


def calibrate_look(detector: Detector, val_good: torch.Tensor) -> None:
    """Set the residual networks' ``look`` of ``detector`` from good validation parts ``val_good`` (N, C, H, W)
    (``look_scores``; ``model.draem.residual``)."""
    assert detector.residual is not None
    detector.residual.calibrate_look(*look_scores(detector, val_good))


@torch.no_grad()
def blend_inputs(detector: Detector, x: torch.Tensor, batch_size: int = 16, around: torch.Tensor | None = None
                 ) -> tuple[np.ndarray, np.ndarray]:
    """What the look's blend is calibrated from (``ResidualDetector.calibrate_blend``), on parts ``x`` (N, C, H, W)
    (and the frame around each, or None): (N,) the variation model's scores with their checks and without the look,
    and (N,) the networks' finding (``Detector.look_finding``), both in the window's units, float64."""
    scores, found = [], []
    for v_scores, logits in _window_and_logits(detector, x, batch_size, around):
        scores.append(v_scores.double().numpy())
        found.append(detector.look_finding(logits).numpy())
    return np.concatenate(scores), np.concatenate(found)


def add_blend(detector: Detector, val_good: torch.Tensor, weight: float, around: torch.Tensor | None = None
              ) -> Detector:
    """A copy of ``detector`` (whose residual networks are its look) whose look is blended
    (``model.draem.residual.blended``): the window's share ``weight``, the two thresholds from ``val_good`` (N, C, H,
    W) good parts (and the frame around each, or None), those of the set its threshold will be set on
    (``blend_inputs``). ModelError when the networks are no look."""
    if detector.residual is None or not detector.residual.looks:
        raise ModelError("the blend weighs the residual networks' finding as the variation model's second look: the "
                         "model has no look (station residual --second-look)")
    if len(val_good) < 2:
        raise ModelError(f"calibrating the blend needs good parts, got {len(val_good)}")
    out = copy.deepcopy(detector).eval()
    assert out.residual is not None
    out.residual.calibrate_blend(weight, *blend_inputs(detector, val_good, around=around))
    out.residual.check()
    return out


@torch.no_grad()
def residual_raw(detector: Detector, x: torch.Tensor, batch_size: int = 16, around: torch.Tensor | None = None
                 ) -> torch.Tensor:
    """(members, N) raw scores of the residual networks of ``detector`` on parts ``x`` (and the frame around each, or
    None), before calibration (what ``ResidualDetector.calibrate`` reads)."""
    assert detector.variation is not None and detector.residual is not None
    raw = []
    for i in range(0, x.shape[0], batch_size):
        v = detector.variation.zmaps(x[i:i + batch_size], signed=True, around=rows(around, i, batch_size))
        assert v.signed is not None and v.judged is not None
        raw.append(detector.residual.raw(*detector.residual_inputs(v.signed, v.judged))[1])
    return torch.cat(raw, 1)
