"""The variation model's second look at a suspicious part: propose and test (rules 45-47,
docs/results/2026-11-28-propose-test.md and docs/results/2026-11-28-cascade.md).

The window statistic looks everywhere, so the good parts' highest place anywhere sets its threshold. The localised
oracle (``localised_oracle``) shows what knowing where a defect is buys. The second look guesses where from the
model's own map and tests there:

1. **Propose** (``proposals``): the ``K`` highest places of the part's window map; around each, the connected region
   where the map stays at or above ``FRACTION`` of that place's peak (at most ``MAX_PX`` pixels, those nearest the
   peak), grown by 1 px. Each region is cleared, grown by 2 px more, before the next place is sought.
2. **Test** (``SecondLook.test``): a region's statistic is the mean over its judged pixels of the chi-square over the
   channels of the part's signed residual (``VariationModel.signed_z``); the same mean over the same pixels for each
   of the good training parts' left-out residuals (the references) gives its good distribution. The region's score is
   its statistic less the references' median, in units of their 95th percentile above the median; the part's test
   score is the largest over its regions.
3. **Gate** (``SecondLook.score``): both the window score and the test score are put in robust standard deviations
   over the good validation parts (median, 1.4826 MAD). A part at or below the window's 5 % threshold on those
   parts (``gate``) keeps its window score; a part above it scores the larger of the two. Every part the window
   passes at 5 % is judged as without the second look, and so is that threshold; the look can only raise a part
   already suspicious. The score comes back in the window score's units.
4. **Gate only** (``tests`` 0; ``station variation --no-second-look-test``): steps 1 and 2 are skipped, and a part
   above the gate keeps its window score; only the residual networks' look (``model.draem.residual``, asked about
   the parts above the gate) can raise it. For a window that already reads a defect's shape (the curvature,
   ``model.draem.variation.CURVATURE_SIGMA``), the test raised good parts more than defective ones
   (docs/results/2026-11-29-curvature.md).

Buffers (sized by the fit, saved with the checkpoint): ``chi`` (R, P) float16, each of R reference parts'
chi-square at the P pixels of the variation model's region (7.5 MB for 376 parts over 9966 pixels); ``judged``
(R, ceil(P / 8)) uint8, their judged pixels as bits (``numpy.packbits``); ``calibration`` (5,) float64 (so that a
good validation part at the gate is not above it by rounding): the gate and the window's and the test's median and
spread over the good validation parts (``CALIBRATION``); ``tests`` 1.0 (propose and test) or 0.0 (the gate only, step
4), which files before it load as 1.0. R = 0: no second look (the model scores as before it
existed). numpy and OpenCV only at scoring time."""

from __future__ import annotations

from typing import TypeVar

import cv2
import numpy as np
import torch
from torch import nn

from .errors import ModelError

Scores = TypeVar("Scores", float, np.ndarray, torch.Tensor)
"""A score or scores, in the window's units or its robust SD (``SecondLook.window_sd``)."""

K = 5
"""How many of the map's highest places are tested."""
FRACTION = 0.5
"""A place's region: where the map stays at or above this share of the place's peak."""
MAX_PX = 400
"""Largest region, in input pixels (the pixels nearest the peak are kept)."""
GATE_FALSE_REJECT = 0.05
"""The second look is for parts above the window score's threshold at this rate of good validation parts."""
TAIL_QUANTILE = 95.0
"""A region's score is in units of the references' TAIL_QUANTILE-th percentile above their median."""
MIN_REFERENCES = 20
"""Fewest reference parts a second look is fitted on (their TAIL_QUANTILE-th percentile needs some); a fit on fewer
good parts has none (``model.draem.with_variation.add_variation``)."""
CALIBRATION = ("gate", "window_location", "window_spread", "test_location", "test_spread")
"""The entries of ``SecondLook.calibration``, in order (the gate in robust SD of the window score)."""


def proposals(window_map: np.ndarray) -> list[np.ndarray]:
    """(H, W) window map (0 where not scored) -> up to ``K`` (H, W) bool regions around its highest places
    (module docstring, step 1), highest first; none where the map is 0 everywhere."""
    out, m = [], np.array(window_map, np.float32)
    for _ in range(K):
        peak = float(m.max())
        if not peak > 0:
            break
        y, x = np.unravel_index(int(m.argmax()), m.shape)
        _, comp = cv2.connectedComponents((m >= FRACTION * peak).astype(np.uint8), connectivity=8)
        reg = comp == comp[y, x]
        if reg.sum() > MAX_PX:
            yy, xx = np.nonzero(reg)
            keep = np.argsort((yy - y) ** 2 + (xx - x) ** 2, kind="stable")[:MAX_PX]
            reg = np.zeros_like(reg)
            reg[yy[keep], xx[keep]] = True
        reg = cv2.dilate(reg.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
        out.append(reg)
        m[cv2.dilate(reg.astype(np.uint8), np.ones((5, 5), np.uint8)).astype(bool)] = 0
    return out


def robust_location_spread(s: np.ndarray) -> tuple[float, float]:
    """(N,) scores of good parts -> (median, 1.4826 MAD + 1e-9): the units the gate and the larger-of are in."""
    s = np.asarray(s, np.float64)
    med = float(np.median(s))
    return med, float(1.4826 * np.median(np.abs(s - med)) + 1e-9)


class SecondLook(nn.Module):
    """Propose and test for a variation model (module docstring). Fitted with ``fit`` on the references, then
    ``calibrate`` on the good validation parts; ``score`` is the identity until both have run."""

    def __init__(self) -> None:
        super().__init__()
        self.register_buffer("calibration", torch.tensor([np.inf, 0.0, 1.0, 0.0, 1.0], dtype=torch.float64))
        self.register_buffer("tests", torch.tensor(1.0))
        self.resize(0, 0)

    def resize(self, references: int, pixels: int) -> None:
        """Empty buffers for ``references`` parts over ``pixels`` region pixels."""
        self.register_buffer("chi", torch.zeros(references, pixels, dtype=torch.float16))
        self.register_buffer("judged", torch.zeros(references, (pixels + 7) // 8, dtype=torch.uint8))

    def size(self, state: dict[str, torch.Tensor], prefix: str, pixels: int) -> None:
        """Give the buffers the shapes they have in ``state`` (keys under ``prefix``; absent: none), so that it loads;
        ModelError when they disagree with each other or with the ``pixels`` of the region."""
        if prefix + "chi" not in state:
            self.resize(0, 0)
            return
        r = len(state[prefix + "chi"])
        want = {"chi": (r, pixels if r else 0), "judged": (r, (pixels + 7) // 8 if r else 0)}
        for name, shape in want.items():
            got = tuple(state[prefix + name].shape) if prefix + name in state else None
            if got != shape:
                raise ModelError(f"variation model: second_look.{name} has shape {got}, {r} references over the "
                                 f"{pixels} pixels of the part region need {shape}")
        self.resize(r, pixels if r else 0)

    @property
    def testing(self) -> bool:
        """Whether a suspicious part's proposed regions are tested (steps 1-2), or only gated for the residual
        networks' look (step 4: ``tests`` 0)."""
        return bool(self.tests > 0)

    @property
    def references(self) -> int:
        """How many reference parts the test puts a region against (0: no second look)."""
        return len(self.chi)

    def fit(self, signed: np.ndarray, region: np.ndarray) -> None:
        """Keep the references: ``signed`` (R, C, H, W) the good training parts' left-out signed residuals
        (``VariationModel.fit``'s return; zero where not judged), ``region`` (H, W) bool the part region."""
        if len(signed) < MIN_REFERENCES:
            raise ModelError(f"second look: {len(signed)} reference parts; its {TAIL_QUANTILE:g}th percentile needs "
                             f">= {MIN_REFERENCES}")
        chi = (np.asarray(signed, np.float32) ** 2).sum(1)[:, region]
        judged = (np.asarray(signed) != 0).any(1)[:, region]
        self.resize(len(chi), int(region.sum()))
        self.chi.copy_(torch.from_numpy(np.minimum(chi, 6e4).astype(np.float16)))
        self.judged.copy_(torch.from_numpy(np.packbits(judged, axis=1)))

    def test(self, window_map: np.ndarray, chi: np.ndarray, judged: np.ndarray, region: np.ndarray) -> float:
        """A part's test score (module docstring, step 2): ``window_map`` (H, W) its window map, ``chi`` (H, W) the
        chi-square over the channels of its signed residual, ``judged`` (H, W) bool its judged pixels, ``region``
        (H, W) bool the region the references are kept over. 0 when nothing is proposed; finite."""
        ref_chi, packed = self.chi.numpy(), self.judged.numpy()
        own = np.where(judged, np.nan_to_num(chi, nan=0.0, posinf=6e4), 0.0)
        best = 0.0
        for reg in proposals(window_map):
            at = np.flatnonzero(reg[region])  # the region's reference pixels: only they are read, not all P
            if not len(at):
                continue
            ref_judged = (packed[:, at >> 3] >> (7 - (at & 7)).astype(np.uint8)) & 1  # numpy.packbits' bit order
            r = ref_chi[:, at].astype(np.float32).sum(1) / np.maximum(ref_judged.sum(1, dtype=np.float32), 1.0)
            mine = float(own[reg].sum()) / max(float(judged[reg].sum()), 1.0)
            med, q = float(np.median(r)), float(np.percentile(r, TAIL_QUANTILE))
            best = max(best, (mine - med) / max(q - med, 1e-6))
        return float(min(best, 1e6))

    def calibrate(self, window_scores: np.ndarray, test_scores: np.ndarray) -> None:
        """Set the gate and the units from the good validation parts' (N,) window scores (without the second look)
        and (N,) test scores (module docstring, step 3)."""
        from .metrics import false_reject_threshold

        wl, ws = robust_location_spread(window_scores)
        tl, ts = robust_location_spread(test_scores)
        gate = false_reject_threshold((np.asarray(window_scores, np.float64) - wl) / ws, GATE_FALSE_REJECT)
        self.calibration.copy_(torch.tensor([gate, wl, ws, tl, ts], dtype=torch.float64))

    def window_sd(self, window_score: Scores) -> Scores:
        """Window scores (a float, array or tensor) -> robust SD over the good validation parts' window scores (the
        units of the gate; ``calibration``'s median and spread)."""
        _, wl, ws = (float(v) for v in self.calibration[:3])
        return (window_score - wl) / ws

    def from_window_sd(self, sd: Scores) -> Scores:
        """``window_sd``'s inverse: robust SD (a float, array or tensor) -> window scores."""
        _, wl, ws = (float(v) for v in self.calibration[:3])
        return wl + ws * sd

    def suspicious(self, window_score: float) -> bool:
        """Whether a part with this window score gets the second look (above the gate; never without references)."""
        return self.references > 0 and self.window_sd(window_score) > float(self.calibration[0])

    def score(self, window_score: float, test_score: float) -> float:
        """A suspicious part's score in the window's units: the larger of its two robust scores (module docstring,
        step 3), mapped back through the window's median and spread."""
        _, wl, ws, tl, ts = (float(v) for v in self.calibration)
        return max(window_score, wl + ws * (test_score - tl) / ts)
