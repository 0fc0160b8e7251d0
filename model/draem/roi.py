"""The region of a frame a network sees (``ModelConfig.roi``), as (top, left, height, width) in pixels; it is
resized to the network's input (``ModelConfig.input_shape``).

Numpy only, so the station's numerics (the presence check) can use the model's region without importing torch.
"""

from __future__ import annotations

import numpy as np

from model.priors.frame_stats import centre_square

from .errors import ModelError


def object_box(object_mask: np.ndarray, margin: float = 0.1) -> tuple[int, int, int, int]:
    """Square (top, left, size, size) box around the object's bounding box, ``margin`` (fraction of its side)
    on each side, clipped to the image where possible; the whole image when the mask is empty."""
    h, w = object_mask.shape
    ys, xs = np.nonzero(object_mask)
    if ys.size == 0:
        s = min(h, w)
        return (h - s) // 2, (w - s) // 2, s, s
    cy, cx = (ys.min() + ys.max() + 1) / 2, (xs.min() + xs.max() + 1) / 2
    side = max(ys.max() - ys.min() + 1, xs.max() - xs.min() + 1) * (1 + 2 * margin)
    side = int(min(max(side, 8), min(h, w)))
    top = int(np.clip(round(cy - side / 2), 0, h - side))
    left = int(np.clip(round(cx - side / 2), 0, w - side))
    return top, left, side, side


def center_box(height: int, width: int, frame_aspect: float = 0.0) -> tuple[int, int, int, int]:
    """The centre square (top, left, side, side) of a height x width frame, for a model trained on frames of
    ``frame_aspect`` (width / height; 0: the frame's own square): ``model.priors.frame_stats.centre_square``."""
    return centre_square(height, width, frame_aspect)


def band_box(height: int, width: int, frame_aspect: float = 0.0) -> tuple[int, int, int, int]:
    """The middle half (in height) of the centre square (``center_box``): (top, left, side // 2, side) of a height x
    width frame; top and left even (the mosaic's 2x2 layout kept), height even. For 640 x 480:
    rows 120-359, columns 80-559, which hold the shipped line's part wherever the fixture's jitter puts it."""
    top, left, side, _ = center_box(height, width, frame_aspect)
    band = (side // 2) & ~1
    return (top + (side - band) // 2) & ~1, left, band, side


def tall_box(height: int, width: int, frame_aspect: float = 0.0) -> tuple[int, int, int, int]:
    """The middle two thirds (in height) of the centre square (``center_box``): (top, left, 2 side // 3, side) of a
    height x width frame, top, left and height even. For 640 x 480: rows 80-399, columns 80-559: the band
    (``band_box``) with 40 rows more above and below it, at the band's detail for an input 1.5 times as wide as high
    (320 x 480 at 128 x 192, as 240 x 480 at 96 x 192), so a part turned a few degrees keeps its ends in view."""
    top, left, side, _ = center_box(height, width, frame_aspect)
    tall = (2 * side // 3) & ~1
    return (top + (side - tall) // 2) & ~1, left, tall, side


AROUND_PX = 16
"""Input pixels of the frame read around the model's view on each side (``around_box``) by the variation model's
registration (``model.draem.variation``, module docstring: around): 40 frame pixels at the shipped band's detail
(240 x 480 at 96 x 192), room for a camera turned 5 degrees to keep the part's ends on real pixels."""


def around_box(box: tuple[int, int, int, int], input_shape: tuple[int, int], around_px: int = AROUND_PX
               ) -> tuple[tuple[int, int, int, int], tuple[int, int]]:
    """A view's (top, left, height, width) frame box and its input shape (H, W) -> the box of the frame around it,
    ``around_px`` input pixels more on each side at the view's detail (rounded to whole frame pixels, so the view
    lies at its centre to within half a frame pixel), and that box's input shape (H + 2 a, W + 2 a). The box may
    reach outside the frame (``model.draem.preprocess.crop_around`` reads NaN there)."""
    top, left, h, w = box
    rows, cols = round(around_px * h / input_shape[0]), round(around_px * w / input_shape[1])
    return ((top - rows, left - cols, h + 2 * rows, w + 2 * cols),
            (input_shape[0] + 2 * around_px, input_shape[1] + 2 * around_px))


def around_px_of(roi: str, priors: tuple[str, ...] | list[str], has_variation: bool) -> int:
    """How many input pixels of the frame around its view a new variation model reads (``AROUND_PX``;
    ``ModelConfig.around_px``, which ``station variation`` sets from this): only a variation model's registration
    reads them, and not for roi "object" (a research crop) or a model reading the normal prior (its estimator sees
    the centre square alone); 0: none."""
    return AROUND_PX if has_variation and roi != "object" and "normal" not in priors else 0


def roi_box(roi: str, shape: tuple[int, int], object_mask: np.ndarray | None = None,
            frame_aspect: float = 0.0) -> tuple[int, int, int, int]:
    """The region a network with ``ModelConfig.roi`` = ``roi`` sees in a frame of ``shape`` (H, W), for a model
    trained on frames of ``frame_aspect`` (``ModelConfig.frame_aspect``; 0: laid out on the frame's own shape)."""
    if roi == "center":
        return center_box(*shape, frame_aspect)
    if roi == "band":
        return band_box(*shape, frame_aspect)
    if roi == "tall":
        return tall_box(*shape, frame_aspect)
    if roi == "frame":
        return 0, 0, shape[0], shape[1]
    if roi == "object":
        if object_mask is None:
            raise ModelError("roi 'object' needs the object mask (ground truth): not available at a station")
        return object_box(object_mask)
    raise ModelError(f"unknown roi {roi!r}")
