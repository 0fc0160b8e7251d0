"""Line variation (exposure and gain drawn per sample), layered --config files, and held-out sets: a set without
them renders and resumes exactly as before."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from sim import dataset as sd
from sim.errors import SimError
from sim.sensor import SensorConfig
from sim.variation import LineVariation

TINY = {"width": 64, "height": 48, "spp": 4}
VARIED = LineVariation(exposure_scale=(0.7, 1.3), analog_gain=(1.0, 2.0))


def test_draws_are_per_sample_within_range_and_reproducible() -> None:
    sensor = SensorConfig(exposure_gain=2.0)
    draws = [VARIED.draw(sensor, 5, i) for i in range(40)]
    scales = [rec["exposure_scale"] for _, rec in draws]
    assert 0.7 <= min(scales) < 0.8 and 1.2 < max(scales) <= 1.3  # spans the range
    for drawn, rec in draws:
        assert drawn.exposure_gain == pytest.approx(2.0 * rec["exposure_scale"])
        assert 1.0 <= drawn.analog_gain <= 2.0 and drawn.bit_depth == sensor.bit_depth
    assert VARIED.draw(sensor, 5, 7) == draws[7] and VARIED.draw(sensor, 6, 7) != draws[7]
    assert LineVariation().draw(sensor, 5, 7) == (sensor, {})  # nothing varies by default


def test_bad_ranges_are_refused_by_name() -> None:
    with pytest.raises(SimError, match=r"variation\.exposure_scale"):
        LineVariation(exposure_scale=(1.3, 0.7))
    with pytest.raises(SimError, match=r"variation\.analog_gain"):
        LineVariation.from_dict({"analog_gain": [0.0, 1.0]})
    with pytest.raises(SimError, match="unknown keys"):
        LineVariation.from_dict({"exposure": [0.7, 1.3]})


def test_variation_changes_brightness_not_the_scene() -> None:
    plain = sd.DatasetSpec(seed=3, defect_fraction=1.0, **TINY)
    varied = sd.DatasetSpec(seed=3, defect_fraction=1.0, variation=VARIED, **TINY)
    model = sd.prepare(plain)
    a, b = sd.generate_sample(plain, model, 0), sd.generate_sample(varied, model, 0)
    assert a.params["scene"] == b.params["scene"] and a.params["defect"] == b.params["defect"]
    assert "sensor" not in a.params
    scale = b.params["sensor"]["exposure_scale"]
    np.testing.assert_allclose(b.s0, a.s0 * scale, rtol=1e-5)  # ground truth is the exposed scene
    ratio = b.raw.astype(float).mean() / a.raw.astype(float).mean()
    assert ratio == pytest.approx(scale, rel=0.1)


def test_manifests_without_new_keys_are_unchanged(tmp_path) -> None:
    d = sd.DatasetSpec().to_dict()
    assert "variation" not in d and "heldout" not in d  # sets rendered before these keys resume
    spec = sd.DatasetSpec.from_dict({**d, "variation": {"exposure_scale": [0.7, 1.3]}})
    assert spec.variation.exposure_scale == (0.7, 1.3)
    assert sd.DatasetSpec.from_dict(spec.to_dict()) == spec


def test_a_heldout_set_is_all_test(tmp_path) -> None:
    spec = sd.DatasetSpec(seed=9, heldout=True, width=8, height=8)
    manifest = sd.init_dataset(tmp_path / "ds", spec, 10)
    assert manifest["split_rule"] == sd.HELDOUT_SPLIT_RULE
    for i in range(10):
        sd.write_sample(tmp_path / "ds", sd.Sample(i, np.zeros((8, 8), np.uint8),
                                                   {"index": i, "split": "test", "label": 0, "defect": None}, 0,
                                                   "test"))
    ds = sd.Dataset(tmp_path / "ds")
    assert ds.indices("test") == list(range(10)) and ds.indices("train") == []
    model = sd.prepare(sd.DatasetSpec(**TINY))
    draw = sd.draw_sample(sd.DatasetSpec(heldout=True, **TINY), model, 5)  # index 5 would be train
    assert draw.split == "test"


def test_a_validation_set_is_all_val_with_defects(tmp_path) -> None:
    spec = sd.DatasetSpec(seed=9, validation=True, width=8, height=8)
    manifest = sd.init_dataset(tmp_path / "ds", spec, 10)
    assert manifest["split_rule"] == sd.VALIDATION_SPLIT_RULE and manifest["config"]["validation"] is True
    for i in range(10):
        sd.write_sample(tmp_path / "ds", sd.Sample(i, np.zeros((8, 8), np.uint8),
                                                   {"index": i, "split": "val", "label": 0, "defect": None}, 0, "val"))
    ds = sd.Dataset(tmp_path / "ds")
    assert ds.indices("val") == list(range(10)) and ds.indices("train") == ds.indices("test") == []
    model = sd.prepare(sd.DatasetSpec(**TINY))
    draws = [sd.draw_sample(sd.DatasetSpec(validation=True, defect_fraction=1.0, **TINY), model, i) for i in (5, 6)]
    assert [d.split for d in draws] == ["val", "val"] and all(d.defect is not None for d in draws)  # train indices
    with pytest.raises(SimError, match="not both"):
        sd.DatasetSpec(heldout=True, validation=True)


def test_config_files_layer_in_order(tmp_path) -> None:
    from station.cli import main

    (tmp_path / "a.toml").write_text('[scene]\ncolour = [0.1, 0.2]\nyaw_deg = [0.0, 1.0]\n[sensor]\nbit_depth = 12\n')
    (tmp_path / "b.toml").write_text('[scene]\ncolour = [0.3, 0.4]\n[variation]\nexposure_scale = [0.9, 1.1]\n')
    merged = sd.read_layers([tmp_path / "a.toml", tmp_path / "b.toml"])
    assert merged == {"scene": {"colour": [0.3, 0.4], "yaw_deg": [0.0, 1.0]}, "sensor": {"bit_depth": 12},
                      "variation": {"exposure_scale": [0.9, 1.1]}}
    out = tmp_path / "set"
    assert main(["render", "--out", str(out), "--count", "1", "--width", "32", "--height", "24", "--spp", "1",
                 "--no-ground-truth", "--config", str(tmp_path / "a.toml"), "--config", str(tmp_path / "b.toml")]) == 0
    config = json.loads((out / "manifest.json").read_text())["config"]
    assert config["scene"]["colour"] == [0.3, 0.4] and config["sensor"]["bit_depth"] == 12
    assert config["variation"]["exposure_scale"] == [0.9, 1.1]


def test_station_render_validation_makes_an_all_val_set_and_refuses_heldout_with_it(tmp_path, capsys) -> None:
    from station.cli import main

    tiny = ["--count", "3", "--width", "32", "--height", "24", "--spp", "1", "--no-ground-truth"]
    out = tmp_path / "val"
    assert main(["render", "--out", str(out), "--validation", *tiny]) == 0
    ds = sd.Dataset(out)
    assert ds.manifest["split_rule"] == sd.VALIDATION_SPLIT_RULE and ds.indices("val") == [0, 1, 2]
    capsys.readouterr()
    assert main(["render", "--out", str(tmp_path / "both"), "--validation", "--heldout", *tiny]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "not both" in err[0]


def test_panel_scale_multiplies_the_panel_and_leaves_every_other_draw() -> None:
    """A panel that ages or is replaced (``panel_scale``): the scene's ``ring_radiance`` times a per-sample factor,
    recorded in the scene; exposure, gain, scene and defect draws as without it; a set without the key keeps its
    manifest; refused without a panel to scale."""
    from sim.scene import SceneConfig

    sensor = SensorConfig(exposure_gain=2.0)
    panel = LineVariation(exposure_scale=(0.7, 1.3), analog_gain=(1.0, 2.0), panel_scale=(0.5, 1.5))
    assert all(panel.draw(sensor, 5, i) == VARIED.draw(sensor, 5, i) for i in range(20))
    factors = [panel.panel(5, i) for i in range(40)]
    assert 0.5 <= min(factors) < 0.6 and 1.4 < max(factors) <= 1.5 and VARIED.panel(5, 0) is None
    lit = SceneConfig(ring_radiance=2.0, ring_elevation_deg=(22.0, 46.0), ring_azimuth_deg=(70.0, 110.0))
    plain = sd.DatasetSpec(seed=3, defect_fraction=1.0, scene=lit, variation=VARIED, **TINY)
    model = sd.prepare(plain)
    a = sd.draw_sample(plain, model, 0)
    for scale in ((1.0, 1.0), (2.0, 2.0)):
        spec = sd.DatasetSpec(seed=3, defect_fraction=1.0, scene=lit, variation=LineVariation(
            exposure_scale=(0.7, 1.3), analog_gain=(1.0, 2.0), panel_scale=scale), **TINY)
        b = sd.draw_sample(spec, model, 0)
        assert b.params.pop("panel_scale") == scale[0] and b.params["ring_radiance"] == 2.0 * scale[0]
        b.params["ring_radiance"] = a.params["ring_radiance"]
        assert b.params == a.params and b.sensor == a.sensor and b.mitsuba_seed == a.mitsuba_seed
        assert b.defect is not None and a.defect is not None and b.defect.info == a.defect.info
        if scale[0] > 1:
            ra, rb = sd.generate_sample(plain, model, 0), sd.generate_sample(spec, model, 0)
            assert rb.params["scene"]["ring_radiance"] == 4.0 and rb.s0.mean() > 1.05 * ra.s0.mean()
        else:  # a factor of 1 renders the same pixels
            np.testing.assert_array_equal(sd.generate_sample(spec, model, 0).raw,
                                          sd.generate_sample(plain, model, 0).raw)
    assert "panel_scale" not in plain.to_dict()["variation"]  # sets rendered before the key resume
    d = spec.to_dict()
    assert d["variation"]["panel_scale"] == [2.0, 2.0] and sd.DatasetSpec.from_dict(d) == spec
    with pytest.raises(SimError, match="panel_scale needs a panel"):
        sd.DatasetSpec(variation=panel)


def test_lens_blur_is_drawn_last_and_blurs_the_frame_not_its_truth() -> None:
    """``lens_blur_px`` (a lens's softness, per sample): drawn after exposure, gain and panel, so those draws and the
    scene are as without it; recorded in ``params.json``'s sensor; a range may start at 0; the frame is softer
    while the ground-truth Stokes are the scene's; a set without the key keeps its manifest."""
    sensor = SensorConfig(exposure_gain=2.0)
    blur = LineVariation(exposure_scale=(0.7, 1.3), analog_gain=(1.0, 2.0), lens_blur_px=(0.0, 1.0))
    for i in range(20):
        (b, rb), (a, ra) = blur.draw(sensor, 5, i), VARIED.draw(sensor, 5, i)
        assert 0.0 <= rb.pop("lens_blur_px") == b.lens_blur_px <= 1.0 and rb == ra
        assert b == replace(a, lens_blur_px=b.lens_blur_px)
    with pytest.raises(SimError, match=r"variation\.lens_blur_px"):
        LineVariation(lens_blur_px=(-0.1, 1.0))
    plain = sd.DatasetSpec(seed=3, defect_fraction=1.0, variation=VARIED, **TINY)
    spec = sd.DatasetSpec(seed=3, defect_fraction=1.0, variation=LineVariation(
        exposure_scale=(0.7, 1.3), analog_gain=(1.0, 2.0), lens_blur_px=(1.5, 1.5)), **TINY)
    model = sd.prepare(plain)
    a, b = sd.generate_sample(plain, model, 0), sd.generate_sample(spec, model, 0)
    np.testing.assert_array_equal(b.s0, a.s0)
    assert b.params["sensor"]["lens_blur_px"] == 1.5 and b.params["scene"] == a.params["scene"]
    lap = [float(np.abs(np.diff(s.raw.astype(float), 2, axis=1)).mean()) for s in (a, b)]
    assert lap[1] < 0.8 * lap[0]  # fewer sharp steps between neighbouring columns
    assert "lens_blur_px" not in plain.to_dict()["variation"]
    assert sd.DatasetSpec.from_dict(spec.to_dict()) == spec


def test_vignetting_is_drawn_after_the_lens_blur() -> None:
    """``vignetting`` (light lost at the corners, per sample) is drawn after every other draw: with it, exposure,
    gain and blur are as without it; it is recorded; its range may start at 0 and must stay below 1."""
    sensor = SensorConfig(exposure_gain=2.0)
    blur = LineVariation(exposure_scale=(0.7, 1.3), analog_gain=(1.0, 2.0), lens_blur_px=(0.0, 1.0))
    both = replace(blur, vignetting=(0.0, 0.3))
    for i in range(20):
        (b, rb), (a, ra) = both.draw(sensor, 5, i), blur.draw(sensor, 5, i)
        assert 0.0 <= rb.pop("vignetting") == b.vignetting <= 0.3 and rb == ra
        assert b == replace(a, vignetting=b.vignetting)
    for bad in ((-0.1, 0.2), (0.1, 1.0)):
        with pytest.raises(SimError, match=r"variation\.vignetting"):
            LineVariation(vignetting=bad)
    assert "vignetting" not in blur.to_dict() and LineVariation.from_dict(both.to_dict()) == both
