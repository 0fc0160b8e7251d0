"""Small synthetic "line" sets for the import, adapt and capture tests: polarized mosaics of one detailed scene
(``model.priors.testing.detailed_stokes``) with per-frame sensor noise, a brightness ``gain`` (exposure) and
bright-patch defects, written in the renderer's dataset format (so the virtual camera and export read them)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import torch

from model.draem.checkpoint import save_checkpoint
from model.draem.config import ModelConfig
from model.draem.detector import Detector
from model.priors.mosaic import stokes_to_mosaic
from model.priors.testing import detailed_stokes
from sim.dataset import DatasetSpec, Sample, init_dataset, split_of, write_sample
from sim.sensor import SensorConfig

W, H = 96, 64


def make_line_set(root: Path, n: int = 20, gain: float = 1.0, bit_depth: int = 8, seed: int = 0,
                  defective: Callable[[int], bool] = lambda i: i % 10 == 1, object_masks: bool = True,
                  kind: Callable[[int], str] = lambda i: "stain", heldout: bool = False,
                  validation: bool = False, blank: Callable[[int], bool] = lambda i: False,
                  polar_only: Callable[[int], bool] = lambda i: False) -> Path:
    """``blank`` samples are all-black good frames (a camera not ready, no part in view); ``polar_only`` ones are
    of one intensity everywhere with a patch polarized unlike the rest (in view for the DoLP presence rule, not for
    the row rule: ``station.presence``)."""
    spec = DatasetSpec(width=W, height=H, seed=seed, sensor=SensorConfig(bit_depth=bit_depth), heldout=heldout,
                       validation=validation)
    init_dataset(root, spec, n)
    s0, s1, s2 = detailed_stokes(H, W)
    full = 2**bit_depth - 1
    rng = np.random.default_rng(seed)
    ideal = stokes_to_mosaic(s0, s1, s2) * 0.8 * gain
    for i in range(n):
        frame = ideal + rng.normal(0.0, 0.01, ideal.shape)
        raw = np.clip(np.round(frame * full), 0, full).astype(np.uint8 if bit_depth <= 8 else np.uint16)
        if blank(i):
            raw[:] = 0
        if polar_only(i):
            flat = np.full((H, W), 0.5)
            q = np.zeros((H, W))
            q[16:48, 24:72] = 0.3  # DoLP 0.6 at AoLP 0 on an unpolarized field
            raw = np.round(stokes_to_mosaic(flat, q, np.zeros((H, W))) * full).astype(raw.dtype)
        mask = np.zeros((H, W), bool)
        if defective(i):
            mask[20:30, 40:50] = True
            raw[mask] = full
        label = int(mask.any())
        split = split_of(i, spec.whole_split)
        write_sample(root, Sample(i, raw, {"index": i, "split": split, "label": label,
                                           "defect": {"type": kind(i)} if label else None}, label, split,
                                  defect_mask=mask, object_mask=np.ones((H, W), bool) if object_masks else None))
    return root


def make_model(path: Path, priors: tuple[str, ...] = ("intensity", "aolp"), seed: int = 0) -> Path:
    det = Detector(ModelConfig.from_preset("tiny", priors, "fused", 32))
    det.init_weights(torch.Generator().manual_seed(seed))
    save_checkpoint(path, det, threshold=0.5, threshold_rule="test")
    return path


def make_segment_set(root: Path, n: int = 40, seed: int = 0, defective: Callable[[int], bool] = lambda i: i % 3 == 1,
                     validation: bool = False) -> Path:
    """A line set imaged as photometric stereo: two frames per part, the dome's +x and -x halves lit in turn
    (``DatasetSpec.dome_segments`` (0, 180)). Every part leans the same way (a tilt along x of +-0.3); a defective
    part has a "dent": a 10 x 10 px patch leaning 0.2 further toward +x. The two frames' mean is the same for every
    part, dent or not, so only the tilt prior (``model.priors.photometric``) can see it; noise is per frame."""
    from sim.scene import SceneConfig

    spec = DatasetSpec(width=W, height=H, seed=seed, validation=validation, dome_segments=(0.0, 180.0),
                       scene=SceneConfig(ambient_gradient=0.8))
    init_dataset(root, spec, n)
    s0, s1, s2 = detailed_stokes(H, W)
    ideal = stokes_to_mosaic(s0, s1, s2) * 0.6
    lean = np.tile(np.linspace(-0.3, 0.3, W, dtype=np.float32), (H, 1))
    rng = np.random.default_rng(seed)
    for i in range(n):
        mask = np.zeros((H, W), bool)
        if defective(i):
            mask[24:34, 40:50] = True
        t = lean + 0.2 * mask
        raws = tuple(np.clip(np.round((ideal * (1 + sign * t) + rng.normal(0.0, 0.01, ideal.shape)) * 255), 0,
                             255).astype(np.uint8) for sign in (1, -1))
        label = int(mask.any())
        split = split_of(i, spec.whole_split)
        write_sample(root, Sample(i, raws[0], {"index": i, "split": split, "label": label,
                                               "defect": {"type": "dent"} if label else None}, label, split,
                                  defect_mask=mask, object_mask=np.ones((H, W), bool), segment_raws=raws))
    return root
