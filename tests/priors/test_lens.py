"""A lens's relative illumination (``model.priors.lens``): the sensor model's vignetting and the look network's lens
copies read one convention; over a view it is the frame's field at the view's place."""

from __future__ import annotations

import numpy as np
import pytest

from model.priors.lens import relative_illumination, view_illumination


def test_a_view_of_the_whole_frame_at_its_own_size_is_the_frames_field() -> None:
    frame = relative_illumination(48, 64, 0.25)
    assert np.array_equal(view_illumination((48, 64), (0, 0, 48, 64), (48, 64), 0.25), frame)
    assert frame[0, 0] == pytest.approx(0.75, abs=1e-6) and (view_illumination((48, 64), (0, 0, 48, 64), (8, 8), 0)
                                                            == 1).all()


def test_a_view_is_its_place_in_the_frame_resized() -> None:
    """The band a model sees (rows 120-359, columns 80-559 of 640 x 480) at 96 x 192: each view pixel the frame's
    field at its centre (within the field's change over a pixel of a 2x2 block mean), symmetric about the frame's
    centre, never darker than the frame's corners."""
    frame = relative_illumination(480, 640, 0.3)
    view = view_illumination((480, 640), (120, 80, 240, 480), (96, 192), 0.3)
    exact = view_illumination((480, 640), (120, 80, 240, 480), (240, 480), 0.3)
    assert np.array_equal(exact, frame[120:360, 80:560])
    coarse = exact.reshape(48, 5, 96, 5).mean((1, 3))  # 5 frame px = 2 view px
    assert np.abs(view.reshape(48, 2, 96, 2).mean((1, 3)) - coarse).max() < 1e-3
    assert np.allclose(view, view[::-1, ::-1], atol=1e-6) and view.min() > frame.min() and view.max() <= 1.0
