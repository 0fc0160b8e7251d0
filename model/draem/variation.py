"""The registered variation model: a member of the detector beside the DRAEM networks that needs no defect to learn.

The fixture puts every part in nearly the same place, so a good part looks like the good parts before it up to a
small warp (the fixture's play, the camera's mounting) and the line's lighting. The classic machine-vision
"variation model" uses that: register each part to a reference, compare every pixel with the statistics of
registered good parts, and flag what lies outside them. Here the comparison allows for the line's shared changes
(a light that moves, a gloss that varies) as a low-rank appearance model, so they do not hide a defect. It is an
anomaly detector by construction (it never saw a defect, so no defect type is "held out" from it), it reads the
same physical priors as the networks, and it fits in about two minutes on a few hundred good training parts.

Convention (all at the network's input: ``ModelConfig.input_shape``, channels as ``config.channel_slices``):
    features  intensity as log(max(I, 1e-3)) minus its median over the part region (exposure and gain are a
              factor on I, an offset here); AoLP as DoLP * (cos 2a, sin 2a) = (S1, S2) / S0 when the model reads
              DoLP (the unit vector's direction is noise where DoLP is low, its Stokes components are not:
              measured on the training set's val split, image AUROC 0.73 with the unit vector, 0.78 with these);
              DoLP itself not as a feature of its own in new fits (``READ_DOLP``: noise biases it, the Stokes
              components carry it); every other channel as is (normals as unit vectors)
    register  an affine warp of the frame's log intensity onto ``reference`` (OpenCV ECC, the correlation coefficient:
              blind to brightness and contrast), started from the identity and, when that finds no plausible warp, again
              from turns about the good parts' median (``RETRY_TURNS_DEG``); a failed or implausible fit (the view's
              centre shifted > 1/4 of a side, scale outside 0.8-1.25) keeps the identity, so the part is compared
              unaligned and scores high. Where the warp reaches outside the frame it replicates the frame's border;
              those pixels are not ``seen`` (``SEEN_LEVEL``), and the outline check reads no edge there: a camera turned
              5 degrees put the belt under the part's left end outside the 96-row input, and its replicated stripes made
              the outline check's largest steps on good parts (docs/results/2026-12-05-seen-edges.md). The shape check
              still reads every column (its robust parabola leaves out those off it; fitted on the seen columns alone it
              spread more: 19 against 7 of 414 good parts of a turned line beyond its threshold), and the window judges
              every pixel of the region, seen or not; the share of the region not seen is a frame check
              (``unseen_fraction``; ``frame_checks.UNSEEN_LIMIT``), so a reject's reason names a part partly outside the
              model's view
    around    the frame around the view (``zmaps``'s ``around``: ``ModelConfig.around_px`` input pixels more on each
              side at the view's detail, NaN beyond the frame; the station and ``station eval`` give it to a file whose
              ``around_px`` is above 0, as the shipped file's since 2026-12-06): the warp is still fitted on the view
              against the reference, but takes its pixels from the frame around, so a part turned or moved a little has
              its ends read from the frame, not made up from the view's border; only beyond the frame around, or beyond
              the frame, is a pixel not seen, and there the frame's border is replicated as the view's was
              (``frame_filled``; not a dark border the window would judge). A refit (``fit``'s ``around``: ``station
              adapt``) reads the frame around as the station will: a refit on the view alone, read with the frame
              around, rejected every good part of a synthetic line whose parts lie 8-18 % outside the view
              (tests/station/test_adapt.py); an adapted file keeps ``around_px``. ``station variation``'s fit and the
              checks' first calibrations read the view alone, as the shipped file's did: on a square line its parts
              barely reach beyond it. On seed 1204's parts seen by a
              camera turned 5 degrees, 2 instead of 10 of 211 good parts rejected (the shape check's 8 gone), as many
              defects caught; on fresh seed 1211 turned 5 degrees 0 instead of 3 of 81, two defective parts fewer of 119
              (docs/results/2026-12-06-view-margin.md)
    turn      how far the warp turns a part onto the reference (``warp_turn_deg``: degrees, positive clockwise as the
              frame is shown), less ``turn_centre``, the median of the good parts the model was calibrated on
              (``calibrate_turn``): the reference lies as its first fitted part lay, the shipped file's good parts
              +4.6 degrees from it. Good parts of the line as built lie within -4.9 to +5.6 degrees of their median
              (the fixture's play); a camera turned by t degrees moves every part's turn by about -t (seeds
              1217-1227, turned 3-20 degrees: -2.8 to -19.8 at the median; docs/results/2026-12-06-turn-check.md). A
              frame check (``turn_deg``; ``frame_checks.TURN_LIMIT_DEG``) and the station's turn monitor
              (``station.drift``)
    appearance  the good parts' registered features, each channel divided by its robust spread over the part
              (``channel_scale``), minus their per-pixel mean: what stays is how a good part differs from the
              average one. Its first ``COMPONENTS`` principal components (``components``) are the line's
              smooth, shared changes (light position and power, material gloss, exposure left after the
              median): a part's residual is what they cannot explain. Measured on the training set's val and
              test splits (270 parts, image AUROC at 0.5x detail): per-pixel median/MAD 0.764, mean-centred
              0.788, 5 components 0.799, 10 components 0.818, 20 0.812, 30 0.812; in the shipped model, on the
              test split, 0.744 -> 0.833. More detail buys nothing here (0.798 at 0.4x and 0.5x, 0.796 at
              0.75x): what hides dents and scratches is the part-to-part variation, not the pixel size; so
              for particles of 0.3-1 mm too (2026-12-01: at twice the shipped detail fewer caught at 1 %, at
              every window, docs/results/2026-12-01-new-kinds/detail.md)
    z map     per pixel and channel residual / scale (scale = 1.4826 MAD of the good parts' residuals, each
              from an appearance fitted without that part (``FOLDS``), floored at the ``floor_quantile`` of the
              scales over the region and at ``MIN_SCALE``, so flat regions do not divide by ~0); the window
              statistic is either |z| maxed over channels and box-averaged over ``box_px`` (``curvature_sigma`` 0,
              files before 2026-11-29), or each channel's curvature: sigma^2 |LoG_sigma * z| of its signed z (the
              Laplacian of a Gaussian of sigma ``curvature_sigma`` input px, scale-normalised), maxed over channels
              (``CURVATURE_SIGMA``); zero outside the eroded part region. Only the judged channels take part
              (``judged_channels``: every feature, unless fitted with fewer, as a judge of the stripes' channels
              alone that reads intensity only to register the part)
    highlights  zero where the part is lit near the sensor's full scale: I (1 + DoLP), the brightest reading
              any polarizer angle can give (``model.priors.conventions``; I alone without the DoLP prior),
              registered with the features, at or above ``HIGHLIGHT_LEVEL``, grown by ``HIGHLIGHT_GROW_PX``.
              A clipped pixel's Stokes are biased and its surface unseen, and the bright lobe around it is a
              second light's specular reflection, which moves with that light: a stray spot on a good part
              scored 13-55 robust SD, above most defects, and these few good parts set the 1 % threshold. On
              the validation set (600 parts, 370 good), caught at 1 % of good parts rejected: 25 % -> 46 %
              (missing studs 21 -> 100 %, stains 71 -> 88 %, chips 27 -> 47 %), at 5 % 53 -> 52 %; a good
              part had 12 % of its region hidden at the 90th percentile, 36 % at most. A defect inside a
              highlight is not judged there. Fail closed: when more than ``MAX_HIDDEN`` of the part would be
              hidden, nothing is (the part scores as without the rule, and a clipped part rejects)
    noise     the z map divided by the frame's own noise level (``noise_level``): the median z over its judged
              pixels and channels against a good part's (``MEDIAN_ABS_NORMAL``), when above 1 and at most
              ``NOISE_CAP``. ``scale`` is the fit line's spread; frames from a noisier camera, gain or renderer
              put every pixel of a good part that many times further out, and a defect covers a small share of
              the part, so the median reads the frame's noise, not its defect. Measured when it was added, before
              ``position`` (thresholds from the validation set): good parts of the same line rendered at 8 spp
              instead of 16 have a level of 1.8 (median), and 25 % of them were rejected at the 5 % threshold,
              none with the rule; the validation and held-out sets' good parts 1.00 (at most 1.38), where image AUROC
              went 0.812 -> 0.813 and 0.834 -> 0.840. One level for all channels: one per channel lowered
              the 8-spp line's AUROC (0.765 -> 0.714), one level kept it (0.751). Blind spot, by design: a
              change spread evenly over most of the part and under NOISE_CAP times the good parts' spread is
              read as noise. ``zmaps`` reports each frame's level and highlight share (``VariationOutput``)
    position  the window statistic (the z map above, after the noise level) put against the good parts' own at the
              same pixel: (w - window_location) / window_spread, zero below; window_location is the median of the
              training parts' window statistics (from their left-out fits) at that pixel, window_spread their
              ``WINDOW_QUANTILE``-th percentile above it, smoothed over ``WINDOW_BLUR_PX`` and floored. Good
              parts' windows are not alike everywhere: at silhouettes, stud edges and where stray light falls they
              run higher and heavier-tailed than on flat faces, so the part's maximum, and with it the threshold,
              was set by a few places. Put per pixel, each place rejects good parts about equally often (a
              constant false-alarm rate), as the localised oracle compares a defect with good parts at its own
              pixels (docs/results/2026-11-24-low-rank-variation.md). On the validation set (prototype on cached
              residuals, docs/results/2026-11-24-position.md), against the uncalibrated window: caught at 1 % of
              good parts rejected 46 % -> 50 % (paired bootstrap SE 2.1), at 5 % 53 % -> 62 % (SE 2.7), image
              AUROC 0.813 -> 0.830 (SE 0.010)
    contrast  (fitted with ``global_contrast``; files before 2026-11-28 have none) the log intensity feature divided
              by the frame's contrast gain c, the least-squares factor that maps the good parts' mean feature onto
              the frame's over the judged pixels: ``MEAN`` all of it (the fitted good parts' too, so their mean is
              that of parts of one contrast), ``RANGE`` only the part beyond the good parts' range, so a frame
              within it is judged as it is. The residual is then taken back to the frame's own units (times the
              gain divided out): the frame is compared with the good parts' pattern scaled by its gain, so its noise
              is not rescaled with its contrast (divided, a low-contrast good part was judged louder and a faint
              scratch on a high-contrast part quieter: docs/results/2026-11-28-contrast-mean/why/). A camera's tone
              response that is a power of I (a gamma g: I -> I^g) multiplies log I, and so the feature (log I minus
              its median), by g; exposure and gain, a factor on I, the median takes out. A defect changes a place,
              not the part's contrast
    smooth field  (``smooth_field`` 1; off in the shipped recipe and in files before 2026-12-07) a lens's
              vignetting, a smooth field in the log intensity feature that no rendered good part had, fitted on
              ``model.draem.smooth_field.smooth_basis`` (a quadratic over the part region) beside the components
              and so taken out of every frame's residual; the good parts lose their own before their components
              are fitted (docs/results/2026-12-09-smooth-field/plan.md)
    clusters  (``clusters`` >= 2; none in files before 2026-11-28) the residual after the components, judged against
              the good parts most like the frame, not against all of them: the fit groups its good parts by their
              components' coefficients (k-means, ``model.draem.appearance_clusters``) and keeps each group's mean
              residual and residual scale over the region; a frame's residual (z) has the mean of the groups near
              it taken out and is divided by their scale (each group weighted by the frame's distance to it)
              before the noise level and the window, and the position calibration is measured on the good parts'
              z so judged, each with its own group without itself.
              The components are linear; a part's yaw, a moving light and the finish change the frame non-linearly
              (a highlight that moves, a mirror image that turns), and one scale per pixel served every kind of
              good part. Screened on the validation set (``APPEARANCE_CLUSTERS``)
    score     max of the map: how far the worst place of the part lies beyond the good parts there, in units of
              their 95th-percentile excess

``Detector.predict`` combines it with the networks (``combine``). numpy + OpenCV at run time (torch only for the
buffers, so the checkpoint carries them); never NaN or Inf.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from typing import NamedTuple

import cv2
import numpy as np
import torch
from torch import nn

from . import appearance_clusters
from .config import Alignment
from .errors import ModelError
from .frame_checks import FRAME_CHECKS, MAX_HIDDEN, NOISE_CAP
from .outline_check import OutlineCheck
from .second_look import SecondLook
from .shape_check import ShapeCheck
from .shifts import Channels, blurred_copies
from .smooth_field import smooth_basis

LOG_FLOOR = 1e-3
"""Intensity below this (full scale) is read as this before the log: black belt and shadows stay finite."""

MIN_SCALE = 0.01
"""Smallest per-pixel scale in feature units (1 % in intensity, 0.01 in DoLP and in cos/sin 2 AoLP): about the
sensor's noise on the part at 12 bits, so a channel that happens to be flat over the good parts (quantised, or
noise-free renders) cannot turn a tiny difference into a huge z."""

COMPONENTS = 10
"""Principal components of good-part appearance taken as the line's own variation (module docstring: appearance).
A fit keeps at most one per 20 parts of the two thirds each fold fits on (``FOLDS``), zeros in the rest: 300 parts
keep all 10, ``station adapt`` on 50 line parts 1 or 2. Components fitted on too few parts follow those parts'
noise, and new good parts then score high."""

GLOBAL_POLARIZATION = Alignment.RANGE
"""The shipped recipe's ``global_polarization`` (``station variation --global-polarization``'s default): how a new
fit puts each frame's polarization onto the good parts' by one frame-wide gain and turn
(``VariationModel.align_polarization``). ``RANGE``, by rule 38 (docs/results/2026-11-28-polarization-range.md,
held-out seed 1136 and the seed-1133 re-renders): against the plain fit, the same image AUROC to four decimals on
the renders (0.8996; the re-renders with another microfacet model, plastic or finish equal too), and under a halved
or doubled DoLP or a 5-degree AoLP offset 0.886-0.899 against 0.826-0.863, with 12.1 %, 3.3 % and 3.8 % of good
parts rejected at its own threshold against 78.0 %, 8.2 % and 47.8 %. ``MEAN`` (rule 37) held those shifts a little
better but cost dents up to 0.027 on one set's renders: it also takes out the good parts' own spread of gains
(0.76-1.28 over the 376 training parts), defects included. A dent does not pull the fitted gain (on the dents
``MEAN`` lost most, with and without the dent's pixels it differs in the third decimal)."""


def shipped_alignment(priors: tuple[str, ...] | list[str]) -> Alignment:
    """The shipped recipe's alignment for a model reading ``priors``: ``GLOBAL_POLARIZATION`` when they include DoLP
    and AoLP, ``OFF`` otherwise (there is no polarization to align)."""
    return GLOBAL_POLARIZATION if {"dolp", "aolp"} <= set(priors) else Alignment.OFF


BLUR_COPIES_SIGMA = 1.5
"""The shipped recipe's ``blur_copies_sigma`` (input px; 0: no blurred copies), ``station variation
--blur-copies``'s default. Copies up to 1.5 px (3.75 px of the 640 x 480 frame) were measured against the fit
without them (docs/results/2026-11-25-frame-shifts.md, rules 9-13 and the full shift bench after them, held-out set
202, thresholds from validation). They hold image AUROC where frames are softer than the renders (the renders use a
box pixel filter, the sharpest there is): under 1 px of blur 0.851 against 0.782, with 9 % of good parts rejected
at the model's own threshold against 23 %; equal on the renders' own frames (validation 0.846 against 0.839, set
212 0.860 against 0.862). But they cost elsewhere: with DoLP halved (a renderer or material that polarizes less)
35 % of good parts were rejected at the own threshold against 5.4 %, and under mild resampling (blur 0.5 px, a
5-degree rotation, a 5 % zoom) 8-10 % at the 5 % threshold against 5-6 %. So they are an option for a line whose
optics are softer than the renders, checked there with ``station bench shift`` and set with ``station adapt``,
not the default. Rule 39 (docs/results/2026-11-28-blur-copies-range.md, the panel line with the polarization range,
held-out seed 1138) measured them again: image AUROC 0.909 against 0.897 on the renders (scratches +0.042, 2.3
paired SE), under 2.5 frame px of blur 0.878 against 0.824 with 22 % of good parts rejected at the own threshold
against 57 %; but with DoLP halved 22 % against 13 % and through a gamma of 1.25 30 % against 16 %. Shipped since
rule 43 (docs/results/2026-11-28-native-units.md, held-out seed 1142), together with ``GLOBAL_CONTRAST`` ``MEAN``
and 8 ``APPEARANCE_CLUSTERS``: with the contrast divided out, the copies' costs above no longer showed (good parts
rejected at the own threshold under 1 px of blur 8.9 % against 49.4 %, with DoLP halved 13.7 % against 15.5 %)."""

APPEARANCE_CLUSTERS = 8
"""The shipped recipe's ``clusters`` (``station variation --clusters``'s default): how many groups of good parts, by
appearance, a new fit judges each part within (module docstring: clusters; ``model.draem.appearance_clusters``);
0: one appearance for every good part. Rule 40 (docs/results/2026-11-28-appearance-clusters.md) measured 8 clusters
against the shipped fit on held-out seed 1139: image AUROC 0.924 against 0.906 (+2.5 paired SE; dents 0.843 against
0.803, scratches 0.815 against 0.781), the same 70 % caught at 1 %. But a frame unlike the renders as a whole is
judged against the few good parts nearest it, whose spread is tighter than all of theirs: at its own threshold it
rejected 96 % of good parts through a gamma of 1.25 (the plain fit 29 %), 40 % with DoLP halved (12 %) and 66 %
under 2.5 frame px of blur (50 %). Shipped since rule 43 (docs/results/2026-11-28-native-units.md), with
``GLOBAL_CONTRAST`` ``MEAN`` and blurred copies, which take out the frame-wide differences that made the nearest
groups' tight spread reject good parts: through a gamma of 1.25 7.7 % against the plain fit's 26.2 %."""

MIN_FIT_PARTS = 8
"""Fewest good parts a fit takes. Far too few for a line: on the validation set, image AUROC was 0.790 with 94 parts,
0.829 with 188, 0.832 with 282 and 376, 0.823 with 755 (docs/results/2026-11-24-data-size-and-features.md)."""

FOLDS = 3
"""The residual scale is measured on parts left out of the appearance fit (each third once)."""

SEEN_LEVEL = 0.999
"""A pixel is ``seen`` when the warp of a frame of ones with a ring of zeros reaches at least this: every pixel it
interpolates lies inside the frame's outermost ring (module docstring: register)."""

MAX_SHIFT = 0.25
"""Largest registration shift of the view's centre, as a fraction of the input's side, still taken as a fit. Until
2026-12-06 the warp's translation was tested instead, its shift at the view's top left corner, which a turn about the
centre moves too: on the shipped file's 96 x 192 input a part turned about the centre beyond -13.7 or +15.6 degrees
from the reference lost its warp and was compared unaligned (docs/results/2026-12-06-turn-check.md)."""

HIGHLIGHT_LEVEL = 1.0
"""I (1 + DoLP), full-scale units, from which a pixel counts as a highlight (module docstring: highlights): where the
brightest polarizer reading can reach full scale. On the validation set, levels 1.0, 0.9 and 0.8 caught 46 %, 47 %
and 47 % at 1 % with a 5 px growth (35-42 % with 2 px), with 0.9 shipped first. But on a brighter line (1.6x
exposure, lighter belt) 0.9 hid a median 16 % of every part, 1.0 1.2 %: a level below full scale hides what is
merely bright, and a line's exposure moves it."""

HIGHLIGHT_GROW_PX = 5
"""Growth of the highlight mask, in input pixels (5 at 96 x 192 is 12 px of the 640 x 480 frame): the bright
specular lobe around a clipped core."""

LATER_BUFFERS = ("window_location", "window_spread", "reads_dolp", "blur_copies_sigma", "global_polarization",
                 "polarization_range", "cluster_centres", "cluster_spread", "cluster_mean", "cluster_scale",
                 "contrast_range", "second_look.calibration", "second_look.chi", "second_look.judged",
                 "curvature_sigma", "second_look.tests", "judged_channels", "shape.edge", "shape.calibration",
                 "outline.edges", "outline.median", "outline.centre", "outline.spread", "outline.calibration",
                 "turn_centre", "smooth_field")
"""Buffers added after the first variation checkpoints were shipped: a checkpoint without them loads with their initial
values (window location 0 and spread 1: the window statistic uncalibrated; ``reads_dolp`` 1: DoLP read as a feature;
``blur_copies_sigma`` 0: fitted without blurred copies; ``global_polarization`` 0: each frame's polarization read as
it is; ``polarization_range`` ``NO_POLARIZATION_RANGE``, which ``MEAN`` files had; no clusters; ``contrast_range``
``CONTRAST_GAIN_RANGE``: contrast judged as it is; no second look; ``curvature_sigma`` 0: the box window;
``second_look.tests`` 1: a second look tests; ``judged_channels`` all 1: every feature judged; ``shape`` NaN: no
shape check; ``outline`` NaN: no outline check; ``turn_centre`` NaN: no turn read, ``calibrate_turn``;
``smooth_field`` 0: no smooth field taken out), which score as those models did. Dotted names are a submodule's
(``nn.Module.get_buffer``)."""

NO_POLARIZATION_RANGE = (1.0, 1.0, 0.0, 0.0)
"""``polarization_range`` (lowest and highest gain, lowest and highest turn) that leaves nothing alone: all of a
frame's gain and turn is divided out (``MEAN``, and the initial value, which older ``MEAN`` files load with)."""

POLARIZATION_GAIN_RANGE = (0.25, 4.0)
"""Range of a frame's polarization gain ``align_polarization`` divides by; beyond it, clamped: a frame with (almost)
no polarization is not blown up to the reference's and a frame polarized far more is not scaled down to it, so
both still read as unlike the good parts."""

CONTRAST_GAIN_RANGE = (0.25, 4.0)
"""Range of a frame's contrast gain (``VariationModel.contrast_factor``): beyond it, clamped. Also the initial
``contrast_range``: a model fitted without the contrast range judges every frame's contrast as it is (any gain lies
within it, so nothing is divided)."""

GLOBAL_CONTRAST = Alignment.MEAN
"""The shipped recipe's ``global_contrast`` (``station variation --global-contrast``; module docstring: contrast):
``MEAN``, with the residual in the frame's own units, 8 ``APPEARANCE_CLUSTERS`` and ``BLUR_COPIES_SIGMA`` 1.5, by
rule 43 (docs/results/2026-11-28-native-units.md, held-out seed 1142, thresholds from validation): image AUROC 0.883
against the plain fit's 0.869 (+1.5 paired SE; dents 0.744 against 0.729, scratches 0.675 against 0.624), good
parts rejected at the own threshold 2.4 % unshifted (4.8 %), through a gamma of 1.25 7.7 % (26.2 %), under 1 px of
blur 8.9 % (49.4 %); the seed-1133 re-renders by other means 0.893-0.900 against 0.879-0.892. Before it:
``RANGE``, rule 41 (docs/results/2026-11-28-contrast-range.md, held-out seed 1140): the good training parts' own
gains span 0.69-1.28 (the line's lights and exposure), so through a gamma of 1.25 most good parts stay within the
range: 25.6 % of them were rejected at the own threshold against 29.7 % without it; every other frame scored as
without it. ``MEAN``, rule 42 (docs/results/2026-11-28-contrast-mean.md, held-out seed 1141), with 8 clusters and
blurred copies (1.5 px): every frame-wide shift held (good parts rejected at the own threshold through a gamma of
1.25 7.1 % against 27.6 %, under 1 px of blur 15.4 % against 56.4 %), but scratches 0.790 against 0.836 (2.3 paired
SE): dividing the frame by its gain rescaled its noise with its contrast (a robust fit of the gain did no better),
which the residual in the frame's own units no longer does (rule 43)."""

SMOOTH_FIELD = False
"""The shipped recipe's ``smooth_field`` (``station variation --smooth-field``): off, until
docs/results/2026-12-09-smooth-field/plan.md's bars are read (module docstring: smooth field)."""

CURVATURE_SIGMA = 3.0
"""The shipped recipe's window statistic (``station variation --curvature``; 0: the box average of the largest
channel's |z| over ``box_px``, as files before it have): the largest channel's scale-normalised Laplacian of a
Gaussian of this sigma (input px) of its signed z (``curvature``). A dent tilts the surface one way on one side and
the other way across it, and a shallow one spreads over 150-390 px at 96 x 192
(docs/results/2026-11-29-second-look.md): |z| averaged over a box adds its faint, opposite-signed pixels to the noise
around them, the curvature of the signed residual adds them with their signs. On the shipped file's fit, the window
alone catches 72.6 % of the validation set's defective parts at 1 % of its good parts rejected with sigma 3, 68.3 %
with the box (dents 43 % and 29 %; sigma chosen there from 1.5-4; docs/results/2026-11-29-curvature.md). With the
second look's test it gains nothing (rule 59); with the look network and no test (``SECOND_LOOK_TEST``) it is the
shipped recipe by rule 60 (held-out seed 1161): 78.8 % caught at 1 % against 74.0 % (+4.8 points, paired SE 1.5;
dents 42 -> 57 %, chips 86 -> 96 %), image AUROC 0.920 against 0.925 (SE 0.008), p99 0.72 times the file before's."""

SECOND_LOOK_TEST = False
"""Whether a new fit's second look tests the regions its map points at (``station variation --second-look-test``;
``model.draem.second_look``, step 2), or only gates the parts its look network is asked about (step 4: the shipped
recipe since rule 60). The test was chosen for the box window (rule 47); on the curvature window it raised good parts
more than defective ones: on the validation set, the window alone caught 71.3 % at 1 %, with the test 65.2 %
(docs/results/2026-11-29-curvature.md)."""

SECOND_LOOK = True
"""The shipped recipe's second look (``station variation --second-look``; ``model.draem.second_look``), by rule 47
(docs/results/2026-11-28-cascade.md, held-out seed 1148, thresholds from validation): defective parts caught at 1 %
of good parts rejected 63.2 % -> 68.2 % (+5.0 points, paired SE 1.6; dents 21 -> 30 %, scratches 35 -> 48 %), at
5 % 77.0 % both, image AUROC 0.908 both. Rule 45 (the larger of the two for every part) and rule 46 (gated with
>=, so the good part at the 5 % threshold was raised and the threshold with it) lost at 5 %."""


READ_DOLP = False
"""Whether a new fit reads DoLP as a feature of its own (module docstring: features). DoLP is the length of the
normalised Stokes vector, and noise lengthens it: the training renders' median DoLP on the part is 0.097 at 16
spp, 0.144 at 8 spp and 0.054 at 64 spp. Read as a feature, a frame less noisy than the renders (a cleaner
renderer, and a real sensor's shot noise is below 16-spp render noise) lies 1.5 robust SD below every good part
everywhere: at the 5 % threshold, 82 % of the good parts of the same line rendered at 64 spp were rejected (3 %
without DoLP). (S1, S2) / S0 have no such bias and carry DoLP as their length. Measured on the variation model
alone, thresholds from the validation set (docs/results/2026-11-24-dolp-bias.md): validation image AUROC 0.832
with DoLP, 0.831 without; caught at 1 % of good parts rejected 49.6 % and 44.3 % (missing studs and chips, whose
DoLP changes, now also seen through their Stokes components); on the 8-spp and brighter lines image AUROC 0.751
and 0.687 with, 0.745 and 0.755 without. Old checkpoints keep reading it (``LATER_BUFFERS``)."""

RETRY_TURNS_DEG = (-20.0, 20.0, -10.0, 10.0)
"""Turns (degrees from the good parts' median turn, ``turn_centre``; from the reference without one) from which ECC
starts again when it finds no plausible warp from the identity (``fitted_warp``). Started from no turn, ECC stopped
reaching the parts of a camera turned -20 degrees: the reference lies +4.6 degrees from the good parts, so those parts
lie about +25 degrees from it, and 73 of 300 warps were not found (fresh seed 1229; the other way, turned 20, none
of 300, about -15 from the reference). A part that registers from the identity, every part of every square set read,
is registered as before (docs/results/2026-12-06-turn-check.md)."""

MAX_TURN_CENTRE = 45.0
"""Largest ``turn_centre`` (degrees) ``check`` accepts: the registration's warp finds a turn of a part it brings onto
its reference, the shipped file's good parts' +4.6; a centre beyond 45 degrees is not a warp that converged."""

MAX_SPREAD = 1e3
"""Largest scale or spread ``check`` accepts: the shipped model's reach 5.5; dividing by 1e30 hides any defect."""

MIN_REGION = 0.01
"""Smallest share of the frame the part region may cover for ``check``: the shipped model's covers 54 %."""

WINDOW_QUANTILE = 95.0
"""``window_spread`` is the good parts' WINDOW_QUANTILE-th percentile of the window statistic above its median, per
pixel (module docstring: position): a tail, because places where good parts run high run heavy-tailed too, and a
robust spread (1.4826 MAD) let their rare high values through (validation set: caught at 5 % 58 % with the MAD,
62 % with this)."""

WINDOW_BLUR_PX = 2.0
"""Gaussian sigma, in input pixels, over which that percentile is smoothed: 376 training parts give a steady 95th
percentile per pixel, ``station adapt``'s 50 parts do not, and neighbouring pixels share their place's tail."""

ABS_NORMAL_SD = 0.6028
"""Standard deviation of |n| for n standard normal. ``window_spread`` is floored at ABS_NORMAL_SD times the
window's gain on independent unit noise (``VariationModel.window_noise``: 1 / box_px for the box), the spread of a
window of independent good pixels: where the good parts agree more closely than that (noise-free renders, floored
scales), a part would otherwise be judged on differences of no physical size."""

MAX_CURVATURE_SIGMA = 16.0
"""Largest ``curvature_sigma`` ``check`` accepts (input px): a wider filter sees the part's outline, not a defect."""


def warp_turn_deg(m: np.ndarray) -> float:
    """(2, 3) affine warp taking the reference's pixels into a frame's (``VariationModel.fitted_warp``) -> how far
    the part lies turned in the frame against the reference, in degrees, positive clockwise as the frame is shown
    (x to the right, y down): atan2 of the warp's first column. 0 for the identity, which a failed fit keeps."""
    return float(np.degrees(np.arctan2(m[1, 0], m[0, 0])))


def turn_about_centre(degrees: float, h: int, w: int) -> np.ndarray:
    """(2, 3) float32 warp that turns an (H, W) view by ``degrees`` about its centre (``warp_turn_deg``'s convention:
    positive clockwise as shown; OpenCV's angle is counter-clockwise as shown), as a start for ECC."""
    return cv2.getRotationMatrix2D(((w - 1) / 2, (h - 1) / 2), -degrees, 1.0).astype(np.float32)


def judged_from(channels: Sequence[int], count: int) -> torch.Tensor:
    """Channel indices -> the (count,) float 0/1 ``judged_channels`` buffer; ModelError for an index outside
    [0, count) or none at all."""
    out = torch.zeros(count)
    for c in channels:
        if not 0 <= int(c) < count:
            raise ModelError(f"judged channel {c} is not one of the model's {count} channels")
        out[int(c)] = 1.0
    if not out.any():
        raise ModelError("the variation model must judge at least one channel")
    return out


def per_part(around: torch.Tensor | None, n: int) -> list[np.ndarray | None]:
    """The frame around each of ``n`` parts as float32 arrays (``zmaps``'s ``around``), or ``n`` Nones without one."""
    return [None] * n if around is None else list(around.float().cpu().numpy())


def ring_inside(in_frame: np.ndarray) -> np.ndarray:
    """(H, W) bool: which pixels of a view (or of the frame around it) the frame holds -> (1, H, W) float32: 1 there,
    0 elsewhere and on the outermost ring. Warped with the border replicated, what is below ``SEEN_LEVEL`` came from
    outside the frame (module docstring: register, around)."""
    inside = np.zeros((1, *in_frame.shape), np.float32)
    inside[0, 1:-1, 1:-1] = in_frame[1:-1, 1:-1]
    return inside


def frame_filled(around: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(C, H, W) priors of the frame around a view, NaN beyond the frame -> (the same, each pixel beyond the frame
    the nearest pixel of the frame's rows and columns in it, as the view's own border is replicated without it;
    (H, W) bool: the pixels in the frame). All NaN: zeros, none in the frame."""
    in_frame = np.isfinite(around).all(0)
    rows, cols = np.flatnonzero(in_frame.any(1)), np.flatnonzero(in_frame.any(0))
    if not len(rows):
        return np.zeros_like(around), in_frame
    (r0, r1), (c0, c1) = (rows[0], rows[-1] + 1), (cols[0], cols[-1] + 1)
    inner = np.nan_to_num(around[:, r0:r1, c0:c1], nan=0.0, posinf=1.0, neginf=0.0)
    h, w = in_frame.shape
    return np.pad(inner, ((0, 0), (r0, h - r1), (c0, w - c1)), mode="edge"), in_frame


def curvature_kernels(sigma: float) -> tuple[np.ndarray, np.ndarray]:
    """Sigma (input px, > 0) -> the 1-D Gaussian g (unit sum) and sigma^2 times its second derivative, sampled over
    +-ceil(4 sigma) px (float32): ``curvature`` filters with g2 along one axis and g along the other, then the other
    way round."""
    radius = max(1, math.ceil(4.0 * sigma))
    t = np.arange(-radius, radius + 1, dtype=np.float64)
    g = np.exp(-0.5 * (t / sigma) ** 2)
    g /= g.sum()
    g2 = (t * t / sigma**2 - 1.0) * g  # sigma^2 d^2g/dt^2
    return g.astype(np.float32), (g2 - g2.mean()).astype(np.float32)  # zero sum: a flat field gives 0


def curvature(z: np.ndarray, sigma: float) -> np.ndarray:
    """(H, W) a channel's signed z -> (H, W) |sigma^2 LoG_sigma * z|, the scale-normalised Laplacian of a Gaussian
    (``curvature_kernels``, borders replicated), float32: a blob of about sigma * sqrt(2) px radius of either sign,
    or a dip opposite across a place, answers; a smooth slope does not."""
    g, g2 = curvature_kernels(sigma)
    z = np.ascontiguousarray(z, np.float32)
    out = (cv2.sepFilter2D(z, cv2.CV_32F, g2, g, borderType=cv2.BORDER_REPLICATE)
           + cv2.sepFilter2D(z, cv2.CV_32F, g, g2, borderType=cv2.BORDER_REPLICATE))
    return np.abs(out)

MEDIAN_ABS_NORMAL = 0.6745
"""Median of |n| for n standard normal: a good part's median z on the fitted line (``scale`` is 1.4826 MAD)."""

SIGNED_CLIP = 20.0
"""``signed_z`` clips each channel's signed residual to +-this many ``scale`` units: beyond it a defect is a defect,
and a frame far off the fitted line (a hostile input) cannot push a network reading it to overflow."""


class VariationOutput(NamedTuple):
    """``VariationModel.zmaps``, per frame of N: ``maps`` (N, H, W) window statistic against the good parts at each
    pixel (module docstring: position), zero off the part and below their median; ``scores`` (N,) their max, or for a
    part above the second look's gate its score (``model.draem.second_look``); ``highlight_fraction`` (N,) the share
    of the part the highlight rule found (above ``MAX_HIDDEN`` none of it was hidden); ``noise_level`` (N,) the
    frame's noise level (1 on the fitted line); ``signed`` (N, C, H, W) each channel's signed residual in units of
    ``scale`` after the noise level (``signed_z``; what the residual networks read, ``model.draem.residual``);
    ``judged`` (N, H, W) bool, the pixels judged; both None unless ``zmaps`` was asked for them; ``edge_bend`` (N,)
    the shape check's bend of each part (``ShapeCheck.bend``; NaN without the check); ``edge_step`` (N,) the outline
    check's step of each part (``OutlineCheck.step``; NaN without the check); ``unseen_fraction`` (N,) the share of
    the part region the registration's warp took from outside the frame (module docstring: register, seen);
    ``turn_deg`` (N,) how far each part lies turned from the good parts the model was calibrated on, degrees,
    positive clockwise as shown (``warp_turn_deg`` less ``turn_centre``; NaN without it or where the warp found no
    plausible fit, module docstring: turn); ``look_level`` (N,) the look network's finding over its blend threshold,
    set by ``Detector.residual_look`` when the file blends (None otherwise)."""

    maps: torch.Tensor
    scores: torch.Tensor
    highlight_fraction: torch.Tensor
    noise_level: torch.Tensor
    signed: torch.Tensor | None = None
    judged: torch.Tensor | None = None
    edge_bend: torch.Tensor | None = None
    edge_step: torch.Tensor | None = None
    unseen_fraction: torch.Tensor | None = None
    turn_deg: torch.Tensor | None = None
    look_level: torch.Tensor | None = None

    def frame_checks(self) -> dict[str, torch.Tensor]:
        """The fields that describe the frame or the part's shape rather than a local defect (``FRAME_CHECKS``), by
        name (those given)."""
        return {name: v for name in FRAME_CHECKS if (v := getattr(self, name)) is not None}


@functools.lru_cache(maxsize=4)
def _region_basis(region: bytes, shape: tuple[int, int], channels: int, intensity: int) -> np.ndarray:
    """``smooth_basis`` of the bool region given as its bytes, read only: each frame of a model reuses its region's
    (2.5 ms a build at 96 x 192 on the 2-core machine, a part's time budget's 2.5 %)."""
    basis = smooth_basis(np.frombuffer(region, bool).reshape(shape), channels, intensity)
    basis.setflags(write=False)
    return basis


class VariationModel(nn.Module):
    """Buffers (saved with the checkpoint): ``reference`` (H, W) log intensity to register to; ``mean`` (C, H, W),
    ``channel_scale`` (C,), ``components`` (COMPONENTS, C, H, W, orthonormal over the region) and ``scale``
    (C, H, W): the good parts' appearance and residual spread (module docstring); ``region`` (H, W) where the
    part is (bool); ``calibration`` (4,): location and spread of the networks' and this model's image scores on
    good validation parts (``combine``); ``window_location``, ``window_spread`` (H, W): median and spread of the
    good parts' window statistic at each pixel (module docstring: position); ``reads_dolp`` 1.0 when DoLP is
    a feature of its own, 0.0 when it is read only through AoLP's Stokes components (``READ_DOLP``;
    ``LATER_BUFFERS``); ``blur_copies_sigma`` the largest blur of the good parts' blurred copies it was fitted with
    (input px, 0: none; ``fit``), which a refit keeps; ``global_polarization`` how each registered frame's
    polarization is first put onto the good parts' by one frame-wide gain and turn (``Alignment.code``;
    ``align_polarization``, ``fit``), which a refit keeps; ``polarization_range`` (4,) the gain's and turn's range
    that ``align_polarization`` leaves alone (lowest and highest gain, lowest and highest turn in radians of AoLP;
    ``NO_POLARIZATION_RANGE`` unless fitted with ``RANGE``); ``cluster_centres`` (M, COMPONENTS) and
    ``cluster_spread`` (COMPONENTS,): the good parts' clusters by appearance (``model.draem.appearance_clusters``;
    M = 0: none), ``cluster_mean`` and ``cluster_scale`` (M, C, P) float16: each cluster's mean residual and
    residual scale at the P pixels of ``region``, in units of ``scale``. ``second_look``: propose and test for
    parts the window finds suspicious (``model.draem.second_look``; no references: none). ``curvature_sigma``: the
    window statistic (module docstring: z map; 0: the box, else the curvature's sigma in input px; ``fit``), which a
    refit keeps. ``judged_channels`` (C,) 1.0 for a channel the window statistic is taken over, 0.0 for one that is
    only read (intensity still registers the part; ``fit``'s ``judged_channels``), which a refit keeps. ``shape``: the
    shape check, how far the part's bottom edge bends (``model.draem.shape_check``; NaN: none). ``outline``: the
    outline check, a short step along the part's long edges (``model.draem.outline_check``; NaN: none). ``intensity``,
    ``dolp``, ``aolp``: the channel index of intensity, of DoLP and of AoLP's cosine (its sine follows), None when
    the model does not read that prior."""

    def __init__(self, channels: int, shape: tuple[int, int], intensity: int, dolp: int | None = None,
                 aolp: int | None = None, box_px: int = 5) -> None:
        super().__init__()
        if box_px < 1 or box_px % 2 == 0:
            raise ModelError(f"variation box_px must be odd and >= 1, got {box_px}")
        h, w = shape
        self.intensity, self.dolp, self.aolp, self.box_px = intensity, dolp, aolp, box_px
        self.register_buffer("reference", torch.zeros(h, w))
        self.register_buffer("mean", torch.zeros(channels, h, w))
        self.register_buffer("channel_scale", torch.ones(channels))
        self.register_buffer("components", torch.zeros(COMPONENTS, channels, h, w))
        self.register_buffer("scale", torch.ones(channels, h, w))
        self.register_buffer("region", torch.ones(h, w, dtype=torch.bool))
        self.register_buffer("calibration", torch.tensor([0.0, 1.0, 0.0, 1.0]))
        self.register_buffer("window_location", torch.zeros(h, w))
        self.register_buffer("window_spread", torch.ones(h, w))
        self.register_buffer("reads_dolp", torch.tensor(1.0))
        self.register_buffer("blur_copies_sigma", torch.tensor(0.0))
        self.register_buffer("global_polarization", torch.tensor(0.0))
        self.register_buffer("polarization_range", torch.tensor(NO_POLARIZATION_RANGE))
        self.register_buffer("contrast_range", torch.tensor(CONTRAST_GAIN_RANGE))
        self.register_buffer("cluster_spread", torch.ones(COMPONENTS))
        self.register_buffer("curvature_sigma", torch.tensor(0.0))
        self.register_buffer("judged_channels", torch.ones(channels))
        self.register_buffer("turn_centre", torch.tensor(math.nan))
        self.register_buffer("smooth_field", torch.tensor(0.0))
        self._resize_clusters(0, 0)
        self.second_look = SecondLook()
        self.shape = ShapeCheck()
        self.outline = OutlineCheck(w)

    def _resize_clusters(self, clusters: int, pixels: int) -> None:
        """Empty cluster buffers for ``clusters`` clusters over ``pixels`` region pixels."""
        channels = len(self.mean)
        self.register_buffer("cluster_centres", torch.zeros(clusters, COMPONENTS))
        self.register_buffer("cluster_mean", torch.zeros(clusters, channels, pixels, dtype=torch.float16))
        self.register_buffer("cluster_scale", torch.ones(clusters, channels, pixels, dtype=torch.float16))

    def size_clusters(self, state: dict[str, torch.Tensor], prefix: str = "") -> None:
        """Give the cluster buffers, whose size is the fit's (clusters, region pixels), the shapes they have in
        ``state`` (a state dict, keys under ``prefix``; without them, none), so that it loads; ModelError when those
        shapes disagree with each other or with ``state``'s region."""
        if prefix + "cluster_centres" not in state:
            self._resize_clusters(0, 0)
            return
        m = len(state[prefix + "cluster_centres"])
        region = state.get(prefix + "region", self.region)
        pixels = int(region.sum()) if m else 0
        want = {"cluster_centres": (m, COMPONENTS), "cluster_mean": (m, len(self.mean), pixels),
                "cluster_scale": (m, len(self.mean), pixels)}
        for name, shape in want.items():
            got = tuple(state[prefix + name].shape) if prefix + name in state else None
            if got != shape:
                raise ModelError(f"variation model: {name} has shape {got}, {m} clusters over the {pixels} pixels "
                                 f"of the part region need {shape}")
        self._resize_clusters(m, pixels)

    def size_fitted(self, state: dict[str, torch.Tensor], prefix: str = "") -> None:
        """``size_clusters``, and the second look's references (``SecondLook.size``) over ``state``'s region: every
        buffer whose size is the fit's takes its shape in ``state``, so that it loads (ModelError as they say)."""
        self.size_clusters(state, prefix)
        region = state.get(prefix + "region", self.region)
        self.second_look.size(state, prefix + "second_look.", int(region.sum()))

    def _load_from_state_dict(self, state_dict: dict[str, torch.Tensor], prefix: str, *args: object,
                              **kwargs: object) -> None:
        if prefix + "cluster_centres" in state_dict:  # sized by the fit: take the state's shapes first
            self.size_clusters(state_dict, prefix)
        if prefix + "second_look.chi" in state_dict:
            self.second_look.size(state_dict, prefix + "second_look.",
                                  int(state_dict.get(prefix + "region", self.region).sum()))
        super()._load_from_state_dict(state_dict, prefix, *args, **kwargs)

    @property
    def clusters(self) -> int:
        """How many clusters of good parts the fit judges within (0: none; ``cluster_centres``)."""
        return len(self.cluster_centres)

    # --- features and registration (numpy) ---

    def features(self, x: np.ndarray, region: np.ndarray | None = None, median: float | None = None) -> np.ndarray:
        """(C, H, W) physical priors -> features (module docstring), float32, finite. ``median``: the log intensity's
        median to take out (the view's, for the frame around it: ``around``); None: its own over the region."""
        f = np.nan_to_num(np.asarray(x, np.float32), nan=0.0, posinf=1.0, neginf=0.0).copy()
        li = np.log(np.maximum(f[self.intensity], LOG_FLOOR))
        f[self.intensity] = li - (self._median_over(li, region) if median is None else median)
        if self.dolp is not None and self.aolp is not None:
            f[self.aolp:self.aolp + 2] *= f[self.dolp]
        if not self.dolp_read:
            f[self.dolp] = 0.0
        return f

    def log_median(self, x: np.ndarray, region: np.ndarray | None = None) -> float:
        """(C, H, W) physical priors -> the median of their log intensity over ``region`` (H, W; None: the part
        region; all pixels when it is empty): what ``features`` takes out."""
        i = np.nan_to_num(np.asarray(x[self.intensity], np.float32), nan=0.0, posinf=1.0, neginf=0.0)
        return self._median_over(np.log(np.maximum(i, LOG_FLOOR)), region)

    def _median_over(self, li: np.ndarray, region: np.ndarray | None) -> float:
        reg = self.region.numpy() if region is None else region
        return float(np.median(li[reg]) if reg.any() else np.median(li))

    @property
    def aligns_polarization(self) -> bool:
        """Whether each frame's polarization is put onto the good parts' first (``align_polarization``)."""
        return self.polarization_alignment is not Alignment.OFF

    @property
    def polarization_alignment(self) -> Alignment:
        """The fit's ``Alignment`` (``global_polarization`` buffer)."""
        modes = list(Alignment)
        return modes[min(max(round(float(self.global_polarization)), 0), len(modes) - 1)]

    def polarization_factor(self, f: np.ndarray, reference: np.ndarray, where: np.ndarray) -> complex:
        """Registered features ``f`` (C, H, W) -> the frame-wide factor k = g e^(2id) that best maps ``reference``'s
        (C, H, W: the good parts' mean features) polarization onto theirs over the pixels ``where`` (H, W), by least
        squares (``align_polarization``), its gain g clamped to ``POLARIZATION_GAIN_RANGE``; 1 without the
        polarization priors, without pixels or without a finite, non-zero fit."""
        a = self.aolp
        if a is None or self.dolp is None or not where.any():
            return 1.0
        q = f[a][where] + 1j * f[a + 1][where]
        m = reference[a][where] + 1j * reference[a + 1][where]
        power = float(np.sum(np.abs(m) ** 2))
        k = complex(np.sum(q * np.conj(m))) / power if power > 1e-12 else 1.0
        if not np.isfinite(k) or k == 0:
            return 1.0
        lo, hi = POLARIZATION_GAIN_RANGE
        return k / abs(k) * min(max(abs(k), lo), hi)

    def align_polarization(self, f: np.ndarray, reference: np.ndarray, where: np.ndarray) -> np.ndarray:
        """Registered features ``f`` (C, H, W) with their polarization divided by the part of the frame-wide gain and
        turn beyond ``polarization_range``, the gain and turn that best map ``reference`` (C, H, W: the good parts'
        mean features) onto them over the pixels ``where`` (H, W).

        Convention: with the Stokes components as one complex number per pixel, q = (S1 + i S2) / S0 = DoLP e^(2ia),
        a frame whose DoLP is g times the good parts' (another renderer's or material's polarization strength, a
        polarizer array's extinction ratio) and whose AoLP is offset by d (a polarizer grid mounted turned, another
        angle reference) reads k q with k = g e^(2id) (``polarization_factor``). k is split as k = c r, r = g' e^(2id')
        with g' and d' the nearest gain and turn within ``polarization_range``, and q_f / c is what is compared (DoLP,
        when read, / |c|): with ``NO_POLARIZATION_RANGE`` (``MEAN``) all of k, with the good parts' own range
        (``RANGE``) only what lies beyond it, so a frame like theirs is compared as it is (to float rounding). Like
        exposure for intensity (a factor on I, the median of log I taken out), it changes the whole part at once,
        where a defect changes a place. Finite for any input; ``f`` unchanged without the polarization."""
        a = self.aolp
        k = self.polarization_factor(f, reference, where)
        if a is None or k == 1.0:
            return f
        g_lo, g_hi, d_lo, d_hi = (float(v) for v in self.polarization_range)
        turn = float(np.angle(k)) / 2.0
        kept = min(max(abs(k), g_lo), g_hi) * np.exp(2j * min(max(turn, d_lo), d_hi))
        c = k / kept
        out = f.copy()
        q = (f[a] + 1j * f[a + 1]) / c
        out[a], out[a + 1] = q.real, q.imag
        if self.dolp_read:
            out[self.dolp] = f[self.dolp] / abs(c)
        return out.astype(np.float32)

    @property
    def aligns_contrast(self) -> bool:
        """Whether frames' contrast is aligned (``contrast_alignment`` not ``OFF``)."""
        return self.contrast_alignment is not Alignment.OFF

    @property
    def contrast_alignment(self) -> Alignment:
        """The fit's contrast ``Alignment``, from its ``contrast_range``: ``CONTRAST_GAIN_RANGE`` (nothing divided)
        ``OFF``, (1, 1) (all of the gain divided) ``MEAN``, a fitted range ``RANGE``."""
        lo_hi = tuple(float(v) for v in self.contrast_range)
        return {CONTRAST_GAIN_RANGE: Alignment.OFF, (1.0, 1.0): Alignment.MEAN}.get(lo_hi, Alignment.RANGE)

    @property
    def takes_smooth_field(self) -> bool:
        """Whether the fit takes a lens's smooth field out of each frame's residual (``smooth_field``)."""
        return float(self.smooth_field) == 1.0

    def _smooth_basis(self) -> np.ndarray:
        """``smooth_basis`` over the part region when the model takes the smooth field out, else (0, C, H, W); read
        only, built once per region (``_region_basis``): it depends on nothing a frame brings."""
        channels = len(self.mean)
        if not self.takes_smooth_field:
            return np.zeros((0, channels, *self.region.shape), np.float32)
        region = self.region.numpy()
        return _region_basis(region.tobytes(), region.shape, channels, self.intensity)

    def contrast_factor(self, f: np.ndarray, where: np.ndarray, reference: np.ndarray | None = None) -> float:
        """Registered features ``f`` (C, H, W) -> the frame-wide gain c that best maps ``reference`` (H, W; None:
        the good parts' mean log intensity feature) onto the frame's log intensity feature over the pixels
        ``where`` (H, W), by least squares, clamped to ``CONTRAST_GAIN_RANGE``; 1 without pixels or without a
        finite, positive fit (``align_contrast``)."""
        if not where.any():
            return 1.0
        m = (self.mean.numpy()[self.intensity] if reference is None else reference)[where]
        q = f[self.intensity][where]
        power = float(np.sum(m.astype(np.float64) ** 2))
        c = float(np.sum(q.astype(np.float64) * m)) / power if power > 1e-12 else 1.0
        if not math.isfinite(c) or c <= 0:
            return 1.0
        lo, hi = CONTRAST_GAIN_RANGE
        return min(max(c, lo), hi)

    def align_contrast(self, f: np.ndarray, where: np.ndarray) -> tuple[np.ndarray, float]:
        """Registered features ``f`` (C, H, W) -> (``f`` with its log intensity feature divided by the part k of the
        frame-wide contrast gain beyond ``contrast_range``, k) (module docstring: contrast; (1, 1), ``MEAN``: all of
        it); (``f`` itself, 1) when the gain lies within it (always, with ``CONTRAST_GAIN_RANGE``: then not even
        measured). The residual of the divided feature times k is the frame against the good parts' pattern scaled
        by k, in the frame's own units (``_judged_residual``)."""
        if not self.aligns_contrast:
            return f, 1.0
        c = self.contrast_factor(f, where)
        lo, hi = (float(v) for v in self.contrast_range)
        kept = min(max(c, lo), hi)
        if kept == c:
            return f, 1.0
        out = f.copy()
        out[self.intensity] = f[self.intensity] * (kept / c)
        return out, c / kept

    @property
    def dolp_read(self) -> bool:
        """Whether DoLP is a feature of its own (``READ_DOLP``); always when there is no AoLP to carry it."""
        return self.dolp is None or self.aolp is None or bool(self.reads_dolp > 0.5)

    def judged_mask(self) -> np.ndarray:
        """(C,) bool: the channels the window statistic is taken over: judged (``judged_channels``) and features
        (without DoLP when it is not read)."""
        keep = self.judged_channels.numpy() > 0.5
        if not self.dolp_read:
            keep[self.dolp] = False
        return keep

    def used(self, z: np.ndarray) -> np.ndarray:
        """(C, ...) per-channel values -> the channels that are judged (``judged_mask``)."""
        keep = self.judged_mask()
        return z if keep.all() else z[keep]

    def peak(self, x: np.ndarray) -> np.ndarray:
        """(C, H, W) physical priors -> (H, W) I (1 + DoLP) (I without the DoLP prior), finite."""
        f = np.nan_to_num(np.asarray(x, np.float32), nan=0.0, posinf=1.0, neginf=0.0)
        return f[self.intensity] * (1.0 + (np.clip(f[self.dolp], 0.0, 1.0) if self.dolp is not None else 0.0))

    @staticmethod
    def highlight(peak: np.ndarray) -> np.ndarray:
        """(H, W) I (1 + DoLP) -> (H, W) bool: at or above ``HIGHLIGHT_LEVEL``, grown by ``HIGHLIGHT_GROW_PX``."""
        grow = np.ones((2 * HIGHLIGHT_GROW_PX + 1,) * 2, np.uint8)
        return cv2.dilate((peak >= HIGHLIGHT_LEVEL).astype(np.uint8), grow).astype(bool)

    def fitted_warp(self, reference: np.ndarray, moving: np.ndarray, mask: np.ndarray | None = None
                    ) -> tuple[np.ndarray, bool]:
        """((2, 3) float32 affine warp taking ``reference``'s (H, W) pixels into ``moving``'s (H, W), whether ECC
        found it) (module docstring: register), matched only where ``mask`` (H, W, of ``moving``) is true when given.
        ECC starts from the identity; when it finds no plausible warp there, it starts again from each of
        ``RETRY_TURNS_DEG`` about the good parts' median turn and keeps the plausible warp of highest correlation;
        the identity and False when none is."""
        m, rho = self._ecc(reference, moving, mask, np.eye(2, 3, dtype=np.float32))
        if m is not None:
            return m, True
        centre = float(self.turn_centre) if math.isfinite(float(self.turn_centre)) else 0.0
        best, best_rho = None, -math.inf
        for turn in RETRY_TURNS_DEG:
            m, rho = self._ecc(reference, moving, mask, turn_about_centre(centre + turn, *reference.shape))
            if m is not None and rho > best_rho:
                best, best_rho = m, rho
        return (np.eye(2, 3, dtype=np.float32), False) if best is None else (best, True)

    @staticmethod
    def _ecc(reference: np.ndarray, moving: np.ndarray, mask: np.ndarray | None, start: np.ndarray
             ) -> tuple[np.ndarray | None, float]:
        """One ECC fit from the warp ``start`` -> (its warp, or None when it fails or is implausible: the view's centre
        shifted beyond ``MAX_SHIFT`` of a side, a scale outside 0.8-1.25; its correlation coefficient)."""
        h, w = reference.shape
        ecc_mask = None if mask is None else mask.astype(np.uint8)
        try:
            rho, m = cv2.findTransformECC(reference, moving, start.copy(), cv2.MOTION_AFFINE,
                                          (cv2.TERM_CRITERIA_EPS | cv2.TERM_CRITERIA_COUNT, 50, 1e-4), ecc_mask, 5)
        except cv2.error:
            return None, -math.inf
        sx, sy = float(np.hypot(*m[:, 0])), float(np.hypot(*m[:, 1]))
        centre = np.array([(w - 1) / 2, (h - 1) / 2, 1.0], np.float32)
        dx, dy = m @ centre - centre[:2]  # the shift of the view's centre: a turn about it moves it not at all
        if (not np.isfinite(m).all() or abs(dx) > MAX_SHIFT * w or abs(dy) > MAX_SHIFT * h
                or not (0.8 <= sx <= 1.25 and 0.8 <= sy <= 1.25)):
            return None, -math.inf
        return m, float(rho)

    def warp_to(self, reference: np.ndarray, f: np.ndarray, mask: np.ndarray | None = None,
                source: np.ndarray | None = None, m: np.ndarray | None = None) -> np.ndarray:
        """Features ``f`` (C, H, W) warped onto ``reference`` (H, W) (module docstring: register), matching only
        where ``mask`` (H, W, of ``f``) is true when given, by the warp ``m`` when given (``fitted_warp``'s, already
        fitted). ``source``: (C, H + 2 m, W + 2 n) the same maps of the frame around ``f`` (``f`` at its centre, m rows
        and n columns more on each side): the warp fitted on ``f`` takes its pixels from it, so it replicates a border
        only beyond the frame around (module docstring: around)."""
        h, w = reference.shape
        if m is None:
            m = self.fitted_warp(reference, f[self.intensity], mask)[0]
        if source is not None:
            m = m.copy()  # the warp maps the reference's pixels into f's; f lies at the source's centre
            m[0, 2] += (source.shape[2] - w) // 2
            m[1, 2] += (source.shape[1] - h) // 2
            f = source
        flags = cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP
        return np.stack([cv2.warpAffine(c, m, (w, h), flags=flags, borderMode=cv2.BORDER_REPLICATE) for c in f])

    # --- fitting ---

    @torch.no_grad()
    def fit(self, x: torch.Tensor, object_mask: torch.Tensor | None = None, floor_quantile: float = 5.0,
            keep_reference: bool = False, blur_copies_sigma: float | None = None,
            global_polarization: Alignment | str | bool | None = None,
            clusters: int | None = None, global_contrast: Alignment | str | None = None,
            curvature_sigma: float | None = None, judged_channels: Sequence[int] | None = None,
            around: torch.Tensor | None = None, smooth_field: bool | None = None) -> np.ndarray:
        """Fit on good parts: ``x`` (N, C, H, W) physical priors, ``object_mask`` (N, H, W) bool where the part is
        (rendered sets have it; None: the whole input). The reference is the first part, then twice the median
        of the first 64 parts registered to it; the region is where at least half of the registered masks lie.
        ``keep_reference``: register to the reference and keep the region already fitted, re-estimating only the
        appearance (mean, components, scales: ``station adapt`` on a line's good parts, which have no object
        masks). Returns the parts' ``signed_z`` (N, C, H, W) float32, each from the appearance fitted without it: what
        ``zmaps`` gives a good part it never saw (in-sample residuals are too small), for ``model.draem.residual``.
        ``blur_copies_sigma`` (input px; None: the model's own, ``blur_copies_sigma`` buffer, so a refit keeps it):
        when above 0, the fit also sees one copy of each part blurred by a Gaussian of sigma uniform in [0, it]
        applied to the Stokes vector (``model.draem.shifts.blurred_copies``), with its part's mask, and left out
        with its part when the residual scale is measured (``FOLDS``); the returned maps are the parts' only. A softer
        lens or another renderer's pixel filter is then among what good parts look like
        (``BLUR_COPIES_SIGMA``). ``global_polarization`` (an ``Alignment``; None: the model's own, so a
        refit keeps it): ``MEAN`` puts each registered part's polarization onto the parts' mean by one frame-wide
        gain and turn before anything is measured (``align_polarization``: twice, the mean taken again after the
        first), and so every frame it judges; ``RANGE`` fits as ``OFF`` and then takes the lowest and highest gain
        and turn of the parts (not their blurred copies) as ``zmaps`` measures them into ``polarization_range``, so
        only frames beyond them are aligned (ModelError for a model without the DoLP and AoLP priors).
        ``clusters`` (None: the model's own count, so a refit keeps it): when 2 or more, the good parts (not their
        blurred copies) are then judged as ``zmaps`` judges a frame, grouped by their components' coefficients
        (``model.draem.appearance_clusters.group``: fewer clusters when there are few parts), each cluster's mean
        residual and scale kept, and the position calibration measured again on each part's clustered z, from its
        cluster without itself; the returned maps are those z (module docstring: clusters). ``global_contrast``
        (an ``Alignment``; None: the model's own, so a refit keeps it): ``MEAN`` divides each registered part's
        log intensity feature by its contrast gain against the parts' mean before anything is measured (twice, the
        mean taken again after the first), and so every frame it judges (``contrast_range`` (1, 1)); ``RANGE`` fits
        as ``OFF`` and then takes the lowest and highest contrast gain of the parts (not their copies) as ``zmaps``
        measures it into ``contrast_range`` (before the clusters), so only frames beyond them are aligned
        (``align_contrast``); ``OFF`` keeps ``CONTRAST_GAIN_RANGE``, which aligns nothing. ``curvature_sigma`` (input
        px; None: the model's own, so a refit keeps it): the window statistic the fit calibrates and the model scores
        with (0: the box; module docstring: z map). ``judged_channels`` (channel indices; None: the model's own, so a
        refit keeps them): the channels the window statistic is taken over; the others are read (intensity still
        registers the part) but not judged. ModelError when none of them is a feature. ``around``: (N, C, H + 2 m,
        W + 2 n) the frame around each part, NaN beyond the frame, read by the registration's warp as ``zmaps``
        reads it (module docstring: around; a blurred copy's frame around is blurred alike); None: the view alone.
        ``smooth_field`` (None: the model's own, so a refit keeps it): take a lens's smooth field out (module
        docstring: smooth field): the good parts' features lose their projection on ``smooth_basis`` before their
        appearance is fitted, and every frame's residual is fitted on it beside the components."""
        xs = x.float().cpu().numpy()
        arounds = per_part(around, len(xs))
        n_parts = len(xs)
        self.reads_dolp.fill_(1.0 if READ_DOLP else 0.0)
        if n_parts < MIN_FIT_PARTS:
            raise ModelError(f"the variation model needs at least {MIN_FIT_PARTS} good parts to fit, got {n_parts}")
        sigma = float(self.blur_copies_sigma) if blur_copies_sigma is None else float(blur_copies_sigma)
        if not (math.isfinite(sigma) and sigma >= 0):
            raise ModelError(f"blur_copies_sigma must be finite and >= 0, got {sigma}")
        curvature_sigma = float(self.curvature_sigma) if curvature_sigma is None else float(curvature_sigma)
        if not 0.0 <= curvature_sigma <= MAX_CURVATURE_SIGMA:
            raise ModelError(f"curvature_sigma must be in [0, {MAX_CURVATURE_SIGMA:g}] input px, got {curvature_sigma}")
        wanted_clusters = self.clusters if clusters is None else int(clusters)
        if wanted_clusters < 0:
            raise ModelError(f"clusters must be >= 0, got {wanted_clusters}")
        contrast = (self.contrast_alignment if global_contrast is None
                    else Alignment.of(global_contrast, "global_contrast"))
        if judged_channels is not None:
            self.judged_channels.copy_(judged_from(judged_channels, len(self.mean)))
        if not self.judged_mask().any():
            raise ModelError("the variation model judges no channel: judged_channels must name a feature other than "
                             "DoLP")
        self.blur_copies_sigma.fill_(sigma)
        self.curvature_sigma.fill_(curvature_sigma)
        if smooth_field is not None:
            self.smooth_field.fill_(1.0 if smooth_field else 0.0)
        mode = (self.polarization_alignment if global_polarization is None
                else Alignment.of(global_polarization))
        if mode is not Alignment.OFF and (self.dolp is None or self.aolp is None):
            raise ModelError("global_polarization needs the DoLP and AoLP priors")
        self.global_polarization.fill_(mode.code)
        self.polarization_range.copy_(torch.tensor(NO_POLARIZATION_RANGE))
        self.contrast_range.copy_(torch.tensor(CONTRAST_GAIN_RANGE))
        self._resize_clusters(0, 0)
        tests = self.second_look.tests.clone()  # the recipe's, which a refit keeps
        self.second_look = SecondLook()  # a new fit's references are its own (``with_variation.add_second_look``)
        self.shape = ShapeCheck()  # and its edge (``with_variation.add_shape_check``)
        self.outline = OutlineCheck(self.outline.median.shape[1])  # (``with_variation.add_outline_check``)
        self.second_look.tests.copy_(tests)
        if sigma > 0:
            channels = Channels(self.intensity, self.dolp, self.aolp)
            xs = np.concatenate([xs, blurred_copies(xs, channels, sigma)])
            # the same sigma per part (one seed); beyond the frame its border replicated first
            arounds += ([None] * n_parts if around is None else
                        list(blurred_copies(np.stack([frame_filled(a)[0] for a in arounds]), channels, sigma)))
            if object_mask is not None:
                object_mask = torch.cat([object_mask, object_mask])
        n = len(xs)
        if keep_reference:
            masks = np.repeat(self.region.numpy()[None], n, 0)
        else:
            masks = (np.ones((n, *xs.shape[2:]), bool) if object_mask is None
                     else object_mask.bool().cpu().numpy())
        feats = [self.features(xi, mi) for xi, mi in zip(xs, masks, strict=True)]
        ref = self.reference.numpy() if keep_reference else feats[0][self.intensity]
        for _ in range(0 if keep_reference else 2):
            ref = np.median(np.stack([self.warp_to(ref, f)[self.intensity] for f in feats[:64]]), 0)
        # each part's mask travels with its features (last channel), so the region is where the registered parts are
        stack = np.stack([self.warp_to(ref, np.concatenate([f, m[None].astype(np.float32)]),
                                       source=self._fit_source(xi, m, a))
                          for xi, f, m, a in zip(xs, feats, masks, arounds, strict=True)])
        region = stack[:, -1].mean(0) >= 0.5
        if not region.any():
            region = np.ones_like(region)
        if keep_reference:
            region = self.region.numpy()
        stack = stack[:, :-1]
        for _ in range(2 if mode is Alignment.MEAN else 0):
            mean_features = stack.mean(0)
            stack = np.stack([self.align_polarization(f, mean_features, region) for f in stack])
        divided = np.ones(n, np.float32)  # each part's contrast gain divided out
        for _ in range(2 if contrast is Alignment.MEAN else 0):
            mean_intensity = stack[:, self.intensity].mean(0)
            gains = np.array([self.contrast_factor(f, region, mean_intensity) for f in stack], np.float32)
            stack[:, self.intensity] /= gains[:, None, None]
            divided *= gains
        spread = 1.4826 * np.median(np.abs(stack - np.median(stack, 0))[:, :, region], axis=(0, 2))
        channel_scale = np.maximum(spread, MIN_SCALE).astype(np.float32)
        u = stack / channel_scale[:, None, None] * region
        if self.takes_smooth_field:  # the good parts without their own smooth field: the components need not hold it
            u = self._residual(u, smooth_basis(region, u.shape[1], self.intensity))[0]
        k = min(COMPONENTS, (n_parts - n_parts // FOLDS) // 20)
        mean, components = self._appearance(u, k)
        # residuals of each part from a fit without it: in-sample ones are too small, the more so the more components;
        # a blurred copy is left out with its part (a fit that saw the copy has all but seen the part)
        residual = np.empty_like(u)
        fold = np.arange(n) % n_parts % FOLDS
        for f in range(FOLDS):
            out = fold == f
            fold_mean, fold_components = self._appearance(u[~out], k)
            residual[out] = self._residual(u[out] - fold_mean, fold_components)[0]
        residual[:, self.intensity] *= divided[:, None, None]  # in each part's own units, as zmaps judges a frame
        scale = 1.4826 * np.median(np.abs(residual), 0)
        floor = np.maximum([np.percentile(s[region], floor_quantile) for s in scale], MIN_SCALE / channel_scale)
        scale = np.maximum(scale, floor[:, None, None])
        signed = np.stack([self.signed_z(r / scale, region) for r in residual])
        windows = np.stack([self.window(r / scale, region)[0] for r in residual])
        location, spread = self._position(windows, region, floor_quantile)
        mean = mean * channel_scale[:, None, None]
        for name, value in (("reference", ref), ("mean", mean), ("channel_scale", channel_scale),
                            ("components", components), ("scale", scale), ("window_location", location),
                            ("window_spread", spread)):
            getattr(self, name).copy_(torch.from_numpy(np.asarray(value, np.float32)))
        self.region.copy_(torch.from_numpy(region))
        self.calibrate_turn(xs[:n_parts], arounds[:n_parts])
        if mode is Alignment.RANGE:
            self.polarization_range.copy_(self._polarization_range(xs[:n_parts], arounds[:n_parts]))
        if contrast is Alignment.MEAN:
            self.contrast_range.fill_(1.0)
        elif contrast is Alignment.RANGE:
            self.contrast_range.copy_(self._contrast_range(xs[:n_parts], arounds[:n_parts]))
        if wanted_clusters >= 2:
            clustered = self._fit_clusters(xs[:n_parts], wanted_clusters, floor_quantile, arounds[:n_parts])
            if clustered is not None:
                return clustered
        return signed[:n_parts]

    def _fit_source(self, xi: np.ndarray, mask: np.ndarray, around: np.ndarray | None) -> np.ndarray | None:
        """(C, H, W) a part's physical priors, (H, W) its mask and (C, H + 2 m, W + 2 n) the frame around it (or None)
        -> what ``fit``'s warp reads the part's features and mask from (``warp_to``'s ``source``): the frame around's
        features (the view's median taken out), the mask's border replicated; None without a frame around."""
        if around is None:
            return None
        filled, _ = frame_filled(around)
        m, n = (filled.shape[1] - mask.shape[0]) // 2, (filled.shape[2] - mask.shape[1]) // 2
        return np.concatenate([self.features(filled, median=self.log_median(xi, mask)),
                               np.pad(mask, ((m, m), (n, n)), mode="edge")[None].astype(np.float32)])

    def _position(self, windows: np.ndarray, region: np.ndarray, floor_quantile: float
                  ) -> tuple[np.ndarray, np.ndarray]:
        """(N, H, W) good parts' window statistics, each from a fit without the part -> (H, W) ``window_location``
        and ``window_spread`` (module docstring: position)."""
        location = np.median(windows, 0)
        spread = cv2.GaussianBlur(np.percentile(windows, WINDOW_QUANTILE, 0) - location, (0, 0), WINDOW_BLUR_PX)
        spread = np.maximum(spread, max(float(np.percentile(spread[region], floor_quantile)),
                                        ABS_NORMAL_SD * self.window_noise()))
        return location, spread

    def _fit_clusters(self, xs: np.ndarray, clusters: int, floor_quantile: float,
                      arounds: Sequence[np.ndarray | None]) -> np.ndarray | None:
        """(N, C, H, W) good parts' physical priors (and the frame around each, or None), after the global fit ->
        their clustered signed z maps (N, C, H, W), each from its cluster without it, with the cluster buffers and the
        position calibration set; None (and no clusters) when ``appearance_clusters.group`` keeps fewer than 2."""
        part = self.region.numpy()
        judged_residuals = [self._judged_residual(xi, a) for xi, a in zip(xs, arounds, strict=True)]
        found = appearance_clusters.group(np.stack([j[1] for j in judged_residuals]), clusters)
        if found is None:
            return None
        centres, spread, labels = found
        r = np.stack([j[0][:, part] for j in judged_residuals])  # (N, C, P)
        stats = [appearance_clusters.residual_stats(r[labels == k]) for k in range(len(centres))]
        signed, windows = [], []
        for i, (ri, coef, judged, _) in enumerate(judged_residuals):
            others = (labels == labels[i]) & (np.arange(len(r)) != i)
            own = list(stats)
            own[labels[i]] = appearance_clusters.residual_stats(r[others])  # its cluster without it
            z = self._unpacked(ri, *appearance_clusters.blend(appearance_clusters.weights(centres, coef / spread),
                                                              own))
            w, level = self.window(z, judged)
            windows.append(w)
            signed.append(self.signed_z(z, judged, level))
        self._resize_clusters(len(centres), int(part.sum()))
        self.cluster_centres.copy_(torch.from_numpy(centres))
        self.cluster_spread.copy_(torch.from_numpy(spread))
        # float16 in the file (its size); clipped so that no hostile fit stores an Inf
        self.cluster_mean.copy_(torch.from_numpy(np.clip(np.stack([m for m, _ in stats]), -1e4, 1e4)))
        self.cluster_scale.copy_(torch.from_numpy(np.minimum(np.stack([s for _, s in stats]), MAX_SPREAD)))
        location, spread_map = self._position(np.stack(windows), part, floor_quantile)
        self.window_location.copy_(torch.from_numpy(location.astype(np.float32)))
        self.window_spread.copy_(torch.from_numpy(spread_map.astype(np.float32)))
        return np.stack(signed)

    def _unpacked(self, r: np.ndarray, mean: np.ndarray, scale: np.ndarray) -> np.ndarray:
        """(C, H, W) residual (z) and a cluster's (C, P) mean and scale over the region's pixels -> the clustered z
        (C, H, W): (r - mean) / scale on the region, r elsewhere."""
        part = self.region.numpy()
        out = r.copy()
        out[:, part] = (r[:, part] - mean) / scale
        return out

    def clustered(self, r: np.ndarray, coef: np.ndarray) -> np.ndarray:
        """(C, H, W) a frame's residual (z) and (COMPONENTS,) its coefficients -> its z against the clusters of good
        parts near it, weighted by distance (``appearance_clusters.weights``; ``r`` itself without clusters)."""
        if not self.clusters:
            return r
        w = appearance_clusters.weights(self.cluster_centres.numpy(), coef / self.cluster_spread.numpy())
        near = np.flatnonzero(w)
        stats = [(self.cluster_mean[k].float().numpy(), self.cluster_scale[k].float().numpy()) for k in near]
        return self._unpacked(r, *appearance_clusters.blend(w[near], stats))

    def calibrate_turn(self, xs: np.ndarray, arounds: Sequence[np.ndarray | None] | None = None) -> float:
        """(N, C, H, W) good parts' physical priors (and the frame around each, or None) -> their median registration
        turn (degrees, ``warp_turn_deg``), kept as ``turn_centre``: ``zmaps`` gives each part's turn from it, so 0 is
        where these good parts lie (module docstring: turn). ``fit`` calls it on its good parts; ``station threshold``
        on the line's good parts (a file fitted before it existed)."""
        arounds = [None] * len(xs) if arounds is None else arounds
        part = self.region.numpy()
        turns = [self._registered(xi, part, a)[3] for xi, a in zip(xs, arounds, strict=True)]
        found = [t for t in turns if math.isfinite(t)]  # a part the warp could not register has no turn
        self.turn_centre.fill_(float(np.median(found)) if found else math.nan)
        return float(self.turn_centre)

    def _contrast_range(self, xs: np.ndarray, arounds: Sequence[np.ndarray | None]) -> torch.Tensor:
        """(N, C, H, W) good parts' physical priors (and the frame around each, or None) -> (2,) lowest and highest
        ``contrast_factor`` as ``zmaps`` measures it (after the fit and its polarization range)."""
        cs = []
        for xi, a in zip(xs, arounds, strict=True):
            warped, _, where, *_ = self._aligned(xi, a)
            cs.append(self.contrast_factor(warped[:-1], where))
        return torch.tensor([min(cs), max(cs)], dtype=torch.float32)

    def _polarization_range(self, xs: np.ndarray, arounds: Sequence[np.ndarray | None]) -> torch.Tensor:
        """(N, C, H, W) good parts' physical priors (and the frame around each, or None) -> (4,) lowest and highest
        gain and turn (radians of AoLP) of their ``polarization_factor`` as ``zmaps`` measures it (after the fit)."""
        mean, part = self.mean.numpy(), self.region.numpy()
        ks = []
        for xi, a in zip(xs, arounds, strict=True):
            warped, judged, *_ = self._registered(xi, part, a)
            ks.append(self.polarization_factor(warped[:-1], mean, judged if judged.any() else part))
        gain, turn = np.abs(ks), np.angle(ks) / 2.0
        return torch.tensor([gain.min(), gain.max(), turn.min(), turn.max()], dtype=torch.float32)

    @staticmethod
    def _appearance(u: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Mean (C, H, W) and first ``k`` principal components (COMPONENTS, C, H, W; zeros beyond k) of ``u``.

        The components are the leading right singular vectors of the centred (N, D) matrix A, found from its (N, N)
        Gram matrix A A^T in float64 (eigenvectors v, then v^T A / sigma): N parts are far fewer than D pixels, so
        one matrix product replaces an SVD of the wide matrix. In torch, on torch's threads (see ``_residual``):
        numpy's SVD ran on its BLAS's own threads and, with the cores busy (a fit beside renders), took 1-4 s a call,
        several calls a fit. Signs are arbitrary, as an SVD's; a direction whose singular value is below 1e-6 of the
        largest or of ``u``'s norm (no variance left, or only float32's rounding of the centring) stays zero rather
        than noise."""
        mean = u.mean(0)
        components = np.zeros((COMPONENTS, *u.shape[1:]), np.float32)
        if k:
            a = torch.from_numpy(np.asarray(u - mean, np.float64).reshape(len(u), -1))
            w, v = torch.linalg.eigh(a @ a.T)  # ascending
            k = min(k, len(u))
            sigma = w.flip(0)[:k].clamp_min(0).sqrt()
            vt = (v.flip(1)[:, :k].T @ a) / sigma.clamp_min(1e-300)[:, None]
            vt[sigma <= 1e-6 * max(float(sigma[0]), float(np.linalg.norm(u)))] = 0  # also float32's centring noise
            components[:k] = vt.float().numpy().reshape(k, *u.shape[1:])
        return mean, components

    @staticmethod
    def _residual(u: np.ndarray, components: np.ndarray, keep: np.ndarray | None = None
                  ) -> tuple[np.ndarray, np.ndarray]:
        """(N, C, H, W) centred, scaled features -> (their residual: minus their projection on ``components`` (K, C,
        H, W), (N, K) the projection's coefficients), fitted by least squares over the pixels ``keep`` (H, W) when
        given (a highlight would otherwise pull every component's coefficient and spread its residual over the whole
        part). In torch, on torch's threads: numpy's BLAS would start its own threads beside torch's, and on 2 cores
        the two pools spinning against each other doubled the station's time per part (71 -> 143 ms p50,
        docs/platform-facts.md)."""
        p = torch.from_numpy(np.ascontiguousarray(components, np.float32)).reshape(len(components), u[0].size)
        flat = torch.from_numpy(np.ascontiguousarray(u, np.float32)).reshape(len(u), -1)
        if keep is None:
            coef = flat @ p.T
        else:
            pw = p * torch.from_numpy(np.broadcast_to(keep, u.shape[1:]).reshape(-1).astype(np.float32))
            gram = pw @ p.T + 1e-6 * torch.eye(len(p))  # the identity when nothing is hidden; unused components: 0
            coef = torch.linalg.solve(gram, pw @ flat.T).T
        return (flat - coef @ p).reshape(u.shape).numpy(), coef.numpy()

    def calibrate(self, network_scores: torch.Tensor, variation_scores: torch.Tensor) -> None:
        """Location (median) and spread (1.4826 MAD, floored) of both image scores on good validation parts."""
        def loc_spread(s: torch.Tensor) -> tuple[float, float]:
            s = s.double()
            med = float(s.median())
            return med, max(1.4826 * float((s - med).abs().median()), 1e-6)

        if len(network_scores) < 2:
            raise ModelError("calibrating the variation model needs good validation parts (at least 2)")
        self.calibration.copy_(torch.tensor([*loc_spread(network_scores), *loc_spread(variation_scores)]))

    def coefficient_entries(self) -> int:
        """How many numbers an appearance coefficient sums over: the part region's pixels times the channels (at
        least 1). A coefficient's spread grows with its square root: ``check`` bounds ``cluster_spread`` divided by
        it (the shipped file 0.94, a fit of intensity and AoLP alone about 10)."""
        return max(int(self.region.sum()), 1) * int(self.components.shape[1])

    def check(self) -> None:
        """ModelError unless every buffer is finite (the shape check's: all NaN or all finite, ``ShapeCheck.check``),
        every scale and spread in (0, ``MAX_SPREAD``] (the clusters' spread per pixel's share,
        ``coefficient_entries``) and the part region at least ``MIN_REGION`` of the frame: a NaN, an empty region or a
        huge spread would pass every part."""
        for name in ("reference", "mean", "channel_scale", "components", "scale", "calibration", *LATER_BUFFERS):
            if name.startswith(("shape.", "outline.")):
                continue  # NaN is their off state (``ShapeCheck.check``, ``OutlineCheck.check``, below)
            if name == "turn_centre":
                if not (math.isnan(float(self.turn_centre)) or abs(float(self.turn_centre)) <= MAX_TURN_CENTRE):
                    raise ModelError(f"variation model: turn_centre is {float(self.turn_centre):g} degrees, beyond "
                                     f"+-{MAX_TURN_CENTRE:g} (NaN: no turn read)")
                continue
            value = self.get_buffer(name)
            if name == "second_look.calibration":
                value = value[1:]  # its gate is infinite until calibrated: no part is looked at again
            if not bool(torch.isfinite(value.float()).all()):
                raise ModelError(f"variation model: {name} has NaN or Inf values")
        spreads = {"channel_scale": self.channel_scale, "scale": self.scale, "window_spread": self.window_spread,
                   "calibration": self.calibration[1::2],
                   # a coefficient sums over every judged pixel and channel: bounded per pixel's share
                   "cluster_spread": self.cluster_spread / math.sqrt(self.coefficient_entries()),
                   "cluster_scale": self.cluster_scale.float(),
                   "second_look.calibration": self.second_look.calibration[2::2]}
        for name, value in spreads.items():
            if not (bool((value > 0).all()) and bool((value <= MAX_SPREAD).all())):
                raise ModelError(f"variation model: {name} has values outside (0, {MAX_SPREAD:g}] "
                                 f"({float(value.min()):.3g} .. {float(value.max()):.3g})")
        judged = self.judged_channels
        if not bool(((judged == 0) | (judged == 1)).all()) or not self.judged_mask().any():
            raise ModelError(f"variation model: judged_channels is {judged.tolist()}: each 0 or 1, at least one "
                             f"feature judged")
        if float(self.smooth_field) not in (0.0, 1.0):
            raise ModelError(f"variation model: smooth_field is {float(self.smooth_field):g}: 0 or 1")
        sigma = float(self.curvature_sigma)
        if not 0.0 <= sigma <= MAX_CURVATURE_SIGMA:  # NaN fails too
            raise ModelError(f"variation model: curvature_sigma is {sigma:g}, outside [0, {MAX_CURVATURE_SIGMA:g}] "
                             f"input px")
        self.shape.check()
        self.outline.check()
        look = self.second_look
        if look.references and look.chi.shape[1] != int(self.region.sum()):
            raise ModelError(f"variation model: second_look.chi covers {look.chi.shape[1]} pixels, the part region "
                             f"{int(self.region.sum())}")
        if float(self.region.float().mean()) < MIN_REGION:
            raise ModelError(f"variation model: region covers {100 * float(self.region.float().mean()):.2f} % of "
                             f"the frame, under {100 * MIN_REGION:g} %: no part to judge")

    # --- scoring ---

    @torch.no_grad()
    def zmaps(self, x: torch.Tensor, signed: bool = False, around: torch.Tensor | None = None) -> VariationOutput:
        """(N, C, H, W) physical priors -> box-averaged z maps, image scores and what each frame's rules found;
        with ``signed``, also each frame's signed maps and judged pixels (for the residual networks; a model
        without them does not pay for them). ``around``: (N, C, H + 2 m, W + 2 n) the priors of the frame around
        each view, NaN where the frame ends (``model.draem.roi.around_box``), read by the registration's warp
        (module docstring: around); None: the warp replicates the view's border."""
        location, spread = self.window_location.numpy(), self.window_spread.numpy()
        region = self.scored_region()
        if not region.any():
            region = self.region.numpy()
        maps, scores, highlights, noise, signed_all, judged_all, bends, steps, unseen, turns = ([] for _ in range(10))
        part = self.region.numpy()
        for xi, ai in zip(x.float().cpu().numpy(), per_part(around, len(x)), strict=True):
            aligned = self._aligned(xi, ai)
            # both before the contrast alignment
            sag = self.shape.sag(aligned[0][self.intensity]) if self.shape.fitted else math.nan
            step = self.outline.step(self.checked_intensity(aligned))
            unseen.append(1.0 - float((aligned[3] & part).sum()) / max(float(part.sum()), 1.0))
            turns.append(aligned[4] - float(self.turn_centre))
            r, coef, judged, hidden = self._residual_of(*aligned[:3])
            highlights.append(hidden)
            r = self.clustered(r, coef)
            w, level = self.window(r, judged)
            noise.append(level)
            if signed:
                signed_all.append(self.signed_z(r, judged, level))
                judged_all.append(judged)
            z = np.maximum((w - location) / spread, 0.0)
            # a NaN here is a number the model could not make: fail closed (it used to read as 0, a pass)
            maps.append(np.where(region & judged, np.nan_to_num(z, nan=1e6, posinf=1e6), 0.0).astype(np.float32))
            scores.append(float(maps[-1].max()))
            if self.second_look.suspicious(scores[-1]) and self.second_look.testing:
                s = signed_all[-1] if signed else self.signed_z(r, judged, level)
                t = self.second_look.test(maps[-1], (s.astype(np.float32) ** 2).sum(0), judged, part)
                scores[-1] = self.second_look.score(scores[-1], t)
            # the largest: each at its own threshold
            scores[-1] = max(scores[-1], self.shape.finding(sag), self.outline.finding(step))
            bends.append(self.shape.bend(sag))
            steps.append(step)
        m = torch.from_numpy(np.stack(maps)).to(x.device)
        return VariationOutput(m, torch.tensor(scores, dtype=torch.float32, device=x.device),
                               torch.tensor(highlights, dtype=torch.float32),
                               torch.tensor(noise, dtype=torch.float32),
                               torch.from_numpy(np.stack(signed_all)) if signed else None,
                               torch.from_numpy(np.stack(judged_all)) if signed else None,
                               torch.tensor(bends, dtype=torch.float32), torch.tensor(steps, dtype=torch.float32),
                               torch.tensor(unseen, dtype=torch.float32), torch.tensor(turns, dtype=torch.float32))

    def _judged_residual(self, xi: np.ndarray, around: np.ndarray | None = None
                         ) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """(C, H, W) physical priors of a frame (and the frame ``around`` it, or None) -> its residual in units of
        ``scale`` (C, H, W) before clusters, its (COMPONENTS,) coefficients, the (H, W) bool pixels judged and the
        share of the part the highlight rule found (module docstring: register, highlights, appearance)."""
        return self._residual_of(*self._aligned(xi, around)[:3])

    def _residual_of(self, warped: np.ndarray, judged: np.ndarray, where: np.ndarray
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """``_judged_residual`` from a frame's ``_aligned`` (its warped features, changed in place, judged pixels and
        the pixels alignments fit over)."""
        mean, part = self.mean.numpy(), self.region.numpy()
        warped[:-1], k = self.align_contrast(warped[:-1], where)
        hidden = 1.0 - judged.sum() / max(part.sum(), 1)
        if judged.sum() < (1.0 - MAX_HIDDEN) * part.sum():
            judged = part  # too much hidden to judge the part by the rest: fail closed
        u = (warped[:-1] - mean) / self.channel_scale.numpy()[:, None, None] * part
        smooth = self._smooth_basis()
        components = np.concatenate([smooth, self.components.numpy()]) if len(smooth) else self.components.numpy()
        r, coef = self._residual(u[None], components, judged)
        r, coef = r[0], coef[:, len(smooth):]  # the appearance's coefficients (the clusters group by them)
        r[self.intensity] *= k  # in the frame's own units: its noise is not rescaled with its contrast
        return r / self.scale.numpy(), coef[0], judged, float(hidden)

    def _aligned(self, xi: np.ndarray, around: np.ndarray | None = None
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, float]:
        """(C, H, W) physical priors (and the frame ``around`` them, or None) -> (``_registered``'s warped features
        with their polarization aligned when the model aligns it, its judged pixels, the pixels alignments fit over:
        those judged, or the part region when none are, its ``seen`` pixels and its warp's turn in degrees)."""
        part = self.region.numpy()
        warped, judged, seen, turn = self._registered(xi, part, around)
        where = judged if judged.any() else part
        if self.aligns_polarization:
            warped[:-1] = self.align_polarization(warped[:-1], self.mean.numpy(), where)
        return warped, judged, where, seen, turn

    def checked_intensity(self, aligned: tuple[np.ndarray, ...]) -> np.ndarray:
        """A frame's ``_aligned`` -> its registered intensity feature as the outline check reads it: NaN where the
        warp took it from outside the frame (module docstring: register), so that no step is read from a border
        the warp made up."""
        return np.where(aligned[3], aligned[0][self.intensity], np.nan)

    def _registered(self, xi: np.ndarray, part: np.ndarray, around: np.ndarray | None = None
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """(C, H, W) physical priors (and the frame ``around`` them, or None) -> (``register``'s warped features with
        I (1 + DoLP) last, (H, W) bool the pixels of the region ``part`` not hidden by a highlight, (H, W) bool
        ``seen``: the pixels the warp took from inside the frame (module docstring: register, around), the warp's
        turn in degrees (``warp_turn_deg``))."""
        median = self.log_median(xi)  # the view's, taken out of the view and of the frame around it alike
        f = self.features(xi, median=median)
        inside = ring_inside(np.ones(xi.shape[1:], bool))
        source = None
        if around is not None:
            filled, in_frame = frame_filled(around)
            source = np.concatenate([self.features(filled, median=median), ring_inside(in_frame),
                                     self.peak(filled)[None]])
        warped, turn = self.register(xi, np.concatenate([f, inside]), source)
        seen = warped[-2] >= SEEN_LEVEL
        warped = np.delete(warped, -2, axis=0)
        return warped, part & ~self.highlight(warped[-1]), seen, turn

    def edge_sag(self, xi: np.ndarray, around: np.ndarray | None = None) -> float:
        """(C, H, W) physical priors of a frame (and the frame ``around`` it, or None) -> the shape check's sag of its
        registered intensity (input px; ``model.draem.shape_check``; NaN without an edge)."""
        return self.shape.sag(self._aligned(xi, around)[0][self.intensity])

    def outline_deviations(self, xi: np.ndarray, around: np.ndarray | None = None) -> np.ndarray:
        """(C, H, W) physical priors of a frame (and the frame ``around`` it, or None) -> the outline check's (2, W)
        deviations of its registered intensity (input px; ``model.draem.outline_check``; all NaN without edges)."""
        return self.outline.deviations(self.checked_intensity(self._aligned(xi, around)))

    def scored_region(self) -> np.ndarray:
        """(H, W) bool: the part region eroded by 1 px (the image border does not erode), where a map is scored: a
        pixel on the region's edge mixes part and background. ``zmaps`` falls back to the whole region when nothing
        is left; the residual networks judge these pixels too (``Detector.residual_inputs``)."""
        return cv2.erode(self.region.numpy().astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)

    def register(self, xi: np.ndarray, f: np.ndarray, source: np.ndarray | None = None
                 ) -> tuple[np.ndarray, float]:
        """(C, H, W) physical priors ``xi`` and (K, H, W) maps ``f`` of the same frame -> (``f`` warped onto the
        reference with the frame's I (1 + DoLP) (``peak``) as its last channel (K + 1, H, W), the warp's turn in
        degrees, ``warp_turn_deg``, NaN when no plausible warp was found): the warp ``zmaps`` uses, matched away
        from highlights unless more than ``MAX_HIDDEN`` of the frame is highlight. ``source``: (K + 1, H + 2 m,
        W + 2 n) the same maps and peak of the frame around ``xi``, read by the warp (``warp_to``)."""
        peak = self.peak(xi)
        seen = ~self.highlight(peak)
        f = np.concatenate([f, peak[None]])
        m, found = self.fitted_warp(self.reference.numpy(), f[self.intensity],
                                    seen if seen.mean() > 1.0 - MAX_HIDDEN else None)
        return self.warp_to(self.reference.numpy(), f, source=source, m=m), warp_turn_deg(m) if found else math.nan

    def register_masks(self, x: torch.Tensor, masks: torch.Tensor) -> torch.Tensor:
        """(N, C, H, W) physical priors and (N, H, W) bool masks of the same frames (a rendered defect's) -> the
        masks in the reference's pixels, as ``zmaps`` registers the frames (bool, (N, H, W))."""
        out = []
        for xi, mi in zip(x.float().cpu().numpy(), masks.cpu().numpy(), strict=True):
            f = np.concatenate([self.features(xi), mi[None].astype(np.float32)])
            out.append(self.register(xi, f)[0][-2] > 0.5)
        return torch.from_numpy(np.stack(out))

    def signed_z(self, r: np.ndarray, judged: np.ndarray, level: float | None = None) -> np.ndarray:
        """(C, H, W) residual in units of ``scale`` and (H, W) judged pixels -> the residual divided by the frame's
        noise level as ``window`` does (``level`` when already known), zero outside ``judged``, clipped to
        +-``SIGNED_CLIP``; float32, finite. A channel that is not a feature (DoLP when not read) is zero: its
        features are; a channel that is not judged (``judged_channels``) is zero too."""
        r = np.nan_to_num(r, nan=0.0, posinf=SIGNED_CLIP, neginf=-SIGNED_CLIP)
        if level is None:
            level = self.noise_level(self.used(np.abs(r)), judged)
        r = r / (level if 1.0 < level <= NOISE_CAP else 1.0)
        if not self.judged_channels.numpy().all():
            r = r * (self.judged_channels.numpy() > 0.5)[:, None, None]
        return (np.clip(r, -SIGNED_CLIP, SIGNED_CLIP) * judged).astype(np.float32)

    def window(self, z: np.ndarray, judged: np.ndarray) -> tuple[np.ndarray, float]:
        """(C, H, W) per-channel signed z of a part and its (H, W) judged pixels -> ((H, W) window statistic after
        the frame's noise level: the largest channel's |z| box-averaged over ``box_px``, or with ``curvature_sigma``
        the largest channel's ``curvature`` of its z, zero outside the judged pixels; the noise level). A channel
        that is not a feature (DoLP when not read) or not judged (``judged_channels``) takes no part."""
        z = self.used(z)
        level = self.noise_level(np.abs(z), judged)
        z = z / (level if 1.0 < level <= NOISE_CAP else 1.0)
        sigma = float(self.curvature_sigma)
        if sigma > 0:
            return np.max([curvature(zc * judged, sigma) for zc in z], 0), level
        return cv2.blur(np.abs(z).max(0), (self.box_px, self.box_px), borderType=cv2.BORDER_REPLICATE), level

    def window_noise(self) -> float:
        """The window statistic's standard deviation, before its absolute value, over independent unit-normal pixels:
        1 / box_px for the box, ||sigma^2 LoG_sigma||_2 for the curvature (``ABS_NORMAL_SD``)."""
        sigma = float(self.curvature_sigma)
        if sigma <= 0:
            return 1.0 / self.box_px
        g, g2 = curvature_kernels(sigma)
        return float(np.sqrt(((np.outer(g2, g) + np.outer(g, g2)) ** 2).sum()))

    @staticmethod
    def noise_level(z: np.ndarray, judged: np.ndarray) -> float:
        """(C, H, W) per-channel z and (H, W) judged pixels -> the frame's noise level: the median z over every
        channel and judged pixel / ``MEDIAN_ABS_NORMAL`` (about 1 on the fitted line's good parts), finite.
        ``zmaps`` divides by it when it lies in (1, ``NOISE_CAP``]: a quiet frame is not made louder, a frame
        beyond the cap is judged as is."""
        s = float(np.median(z[:, judged])) / MEDIAN_ABS_NORMAL if judged.any() else 1.0
        return s if math.isfinite(s) else 1e6


def network_score(member_scores: dict[str, torch.Tensor]) -> torch.Tensor:
    """The networks' image score (mean over network members) from a detector output's ``member_scores``."""
    return torch.stack([v for k, v in member_scores.items() if k not in ("variation", "residual")]).mean(0)


SQUASH_CENTRE = 3.0
"""Combined score = 1/2 + atan(z - SQUASH_CENTRE) / pi: a part 3 robust standard deviations above the good parts in
either detector scores 0.5; kept in [0, 1] like every image score of the project (thresholds are checked in
[0, 1]). Not a sigmoid: that reaches 1.0 in float32 at z of about 20, which defects pass easily, and a threshold of
1.0 can never be exceeded (an adapted threshold of exactly 1 would pass every part). 1 - score falls as
1 / (pi z), distinct in float32 up to z of about 1e6."""


def squash(z: torch.Tensor) -> torch.Tensor:
    return 0.5 + torch.atan(z - SQUASH_CENTRE) / math.pi


def combine(network_map: torch.Tensor, network_score: torch.Tensor, variation_map: torch.Tensor,
            variation_score: torch.Tensor, calibration: torch.Tensor, networks: bool = True
            ) -> tuple[torch.Tensor, torch.Tensor]:
    """The detector's map and score from the networks' and the variation model's: each put in robust standard
    deviations above its good validation parts (``calibration`` = network location, spread, variation location,
    spread), the larger taken (either detector's finding rejects the part), then ``squash``. Pixel maps use the
    image calibration. ``networks`` False: the variation model's finding alone (``ModelConfig.decision``).
    Returns ((N, H, W) map, (N,) score), both in [0, 1]."""
    return (combined_score(network_map, variation_map, calibration, networks),
            combined_score(network_score, variation_score, calibration, networks))


def combined_score(network: torch.Tensor, variation: torch.Tensor, calibration: torch.Tensor,
                   networks: bool = True) -> torch.Tensor:
    """``combine``'s rule on scores (or maps) of any shape: squash(max((n - dl) / ds, (v - vl) / vs)), or
    squash((v - vl) / vs) without the ``networks``."""
    dl, ds, vl, vs = (float(c) for c in calibration)
    zn, zv = (network.float() - dl) / ds, (variation.float().to(network.device) - vl) / vs
    return squash(torch.maximum(zn, zv) if networks else zv).float()

