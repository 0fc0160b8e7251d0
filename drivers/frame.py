"""The one frame type every camera delivers: a raw polarization mosaic plus where and when it came from.

The mosaic is what the sensor gave, decoded from the wire format (``drivers.pixel_formats``) to uint8 or uint16
codes of ``bit_depth`` significant bits; its polarizer layout is ``model.priors.conventions`` (IMX250MZR by
default). A simulated frame also carries its ground truth so the station can score its decisions live.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

FRAME_SCHEMA_VERSION = 1
"""Bumped when a Frame field changes meaning (stored with logged frames)."""


@dataclass(frozen=True, eq=False)
class GroundTruth:
    """What a simulated part really is.

    label        1 if the part has a defect (``defect_mask`` non-empty), else 0 (also 0 when no part is in view).
    defect_mask  (H, W) bool, True on defect pixels, same shape as the frame's mosaic; None if not known.
    sample_index index of the rendered sample in its dataset (None when rendered on the fly).
    split        the sample's split in its dataset ("train" | "val" | "test"), or None.
    params       every sampled scene parameter (pose, material, defect type...), as in ``params.json``.
    present      False when the frame shows no part (an empty scene: ``"empty": true`` in ``params.json``).
    """

    label: int
    defect_mask: np.ndarray | None = None
    sample_index: int | None = None
    split: str | None = None
    params: dict[str, Any] = field(default_factory=dict)
    present: bool = True


@dataclass(frozen=True, eq=False)
class Frame:
    """One image from a camera.

    raw               (height, width) uint8 or uint16 mosaic, C-contiguous, owned by the frame (never a view
                      of a driver buffer that is reused).
    pixel_format      the wire format's name ("Mono8", "Mono12p", "PolarizeMono12p", ...).
    bit_depth         significant bits of each code (8, 10, 12, 16): full scale is ``2**bit_depth - 1``.
    frame_id          monotonic frame counter: the camera's id unwrapped past its 16-bit wrap (GigE Vision 1.x),
                      so a gap between two frames' ids is the number of frames lost in between.
    device_frame_id   the id exactly as the camera sent it (wraps; 0 is never used by GigE Vision).
    timestamp_ns      the camera's timestamp in nanoseconds (its own clock; 0 if it sends none).
    host_timestamp_ns ``time.time_ns()``-clock time when the host completed the frame.
    ground_truth      set for simulated frames only.
    companion         the second camera's frame of the same part (``drivers.camera_pair.CameraPair``); None with
                      one camera.
    """

    raw: np.ndarray
    pixel_format: str
    bit_depth: int
    frame_id: int
    timestamp_ns: int
    host_timestamp_ns: int
    device_frame_id: int | None = None
    ground_truth: GroundTruth | None = None
    companion: Frame | None = None

    def __post_init__(self) -> None:
        if self.raw.ndim != 2 or self.raw.dtype not in (np.uint8, np.uint16):
            raise ValueError(f"frame {self.frame_id}: raw mosaic must be a 2-D uint8/uint16 array, "
                             f"got shape {self.raw.shape} dtype {self.raw.dtype}")
        if not 1 <= self.bit_depth <= self.raw.dtype.itemsize * 8:
            raise ValueError(f"frame {self.frame_id}: bit depth {self.bit_depth} does not fit {self.raw.dtype}")

    @property
    def height(self) -> int:
        return int(self.raw.shape[0])

    @property
    def width(self) -> int:
        return int(self.raw.shape[1])

    @property
    def full_scale(self) -> int:
        """Largest code: ``2**bit_depth - 1``."""
        return 2**self.bit_depth - 1
