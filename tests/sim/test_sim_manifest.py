"""A dataset's manifest.json that is not the renderer's is one error naming the file and key (every command that
reads a set: train, eval, threshold, adapt, run, export, serve-camera), never a traceback; and station render refuses
an output folder it would spoil."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from sim.dataset import DatasetSpec, init_dataset, open_dataset
from sim.errors import SimError


@pytest.mark.parametrize(("content", "message"), [
    (b"\xff\xfe\x00", "unreadable manifest"),
    (b"[1, 2]", "expected a JSON object"),
    (None, "bit_depth: 99"),
    (None, "layout: 'bogus'"),
])
def test_a_foreign_or_damaged_manifest_is_one_error_naming_it(tmp_path: Path, content: bytes | None,
                                                             message: str) -> None:
    root = tmp_path / "set"
    init_dataset(root, DatasetSpec(width=16, height=8), 2)
    path = root / "manifest.json"
    if content is None:
        manifest = json.loads(path.read_text())
        manifest.update({"bit_depth": 99} if "bit_depth" in message else {"layout": "bogus"})
        content = json.dumps(manifest).encode()
    path.write_bytes(content)
    with pytest.raises(SimError, match=rf"manifest.json: .*{message}"):
        open_dataset(root)
    if message in ("unreadable manifest", "expected a JSON object"):  # resuming a render reads it too
        with pytest.raises(SimError, match=rf"manifest.json: .*{message}"):
            init_dataset(root, DatasetSpec(width=16, height=8), 2)


@pytest.mark.parametrize(("argv", "message"), [
    (["--out", "", "--count", "2"], "--out: empty"),
    (["--out", "{tmp}/model", "--count", "2"], "not a data set"),
    (["--out", "{tmp}/set", "--count", "99999999999999999999"], "--count"),
    (["--out", "{tmp}/set", "--count", "2", "--mesh-scale", "nan"], "mesh_scale"),
])
def test_render_refuses_an_output_it_would_spoil_and_numbers_it_cannot_render(tmp_path: Path, capsys, monkeypatch,
                                                                              argv, message):
    """`--out ""` rendered into the working directory, a model folder got a manifest.json and samples/ written into
    it, a huge --count hung building its index list, and --mesh-scale nan was written into the manifest."""
    from station.cli import main

    monkeypatch.chdir(tmp_path)  # where `--out ""` rendered
    (tmp_path / "model").mkdir()
    (tmp_path / "model" / "best.pt").write_bytes(b"weights")
    assert main(["render", *[a.format(tmp=tmp_path) for a in argv]]) == 2
    assert message in capsys.readouterr().err
    assert sorted(p.name for p in (tmp_path / "model").iterdir()) == ["best.pt"]


@pytest.mark.parametrize(("flag", "expected"), [([], 12), (["--bit-depth", "8"], 8), (["--bit-depth", "16"], 16)])
def test_a_bit_depth_on_the_command_line_wins_over_the_presets(tmp_path: Path, flag: list[str], expected: int) -> None:
    """sim/presets/line-polar.toml sets [sensor] bit_depth = 12; `--bit-depth 8` was silently ignored beside it (the
    set was rendered at 12 bits, its manifest said so, and nothing told the user)."""
    from station.cli import main

    out = tmp_path / "set"
    assert main(["render", "--out", str(out), "--count", "1", "--width", "32", "--height", "24", "--spp", "1",
                 "--no-ground-truth", "--config", "sim/presets/line-polar.toml", *flag]) == 0
    assert json.loads((out / "manifest.json").read_text())["bit_depth"] == expected


@pytest.mark.parametrize(("written", "resumes"), [
    ({}, True),  # before the ring light existed
    ({"ring_radiance": 0.0, "ring_elevation_deg": [5.0, 15.0]}, True),  # the ring's keys at their defaults
    ({"ring_radiance": 5.0, "ring_elevation_deg": [5.0, 15.0]}, False),  # a set lit by a ring is another set
    ({"ring_fringe_period_deg": 0.0, "ring_fringe_depth": 0.5}, True),  # no fringes
    ({"ring_fringe_phase_deg": 0.0}, True),  # the fringes' phase at its default
    ({"front_light_radiance": 0.0, "front_light_span_m": [0.011, 0.04]}, True),  # the front light off
    ({"front_light_radiance": 2.1}, False),  # a set with a front light is another set
])
def test_a_set_written_by_earlier_code_resumes_when_it_drew_the_same(tmp_path: Path, written: dict,
                                                                      resumes: bool) -> None:
    """The ring light's keys went into every manifest, at their defaults too, and manifests were compared key
    for key: no set rendered before it resumed ("describes a different dataset"). A key at its default, written or
    not, now reads the same; a key that changes the set still refuses."""
    root = tmp_path / "set"
    init_dataset(root, DatasetSpec(width=16, height=8), 2)
    path = root / "manifest.json"
    manifest = json.loads(path.read_text())
    manifest["config"]["scene"] = {k: v for k, v in manifest["config"]["scene"].items() if "ring" not in k} | written
    path.write_text(json.dumps(manifest))
    if resumes:
        init_dataset(root, DatasetSpec(width=16, height=8), 4)
        assert json.loads(path.read_text())["count"] == 4
    else:
        with pytest.raises(SimError, match="describes a different dataset"):
            init_dataset(root, DatasetSpec(width=16, height=8), 4)


def test_a_set_rendered_without_the_oracle_resumes_with_it(tmp_path: Path) -> None:
    """`IGNORED_ON_RESUME` names `visibility` (the detectability oracle measures a sample, it does not change it), but
    the spec's `visibility` went into the manifest's config too, which was compared key for key: a held-out set
    rendered without `--visibility` refused `make model`'s held-out render of the same parts ("describes a different
    dataset"). A set with other parts still refuses."""
    root = tmp_path / "set"
    init_dataset(root, DatasetSpec(width=16, height=8), 2)
    init_dataset(root, DatasetSpec(width=16, height=8, visibility=True), 4)
    assert json.loads((root / "manifest.json").read_text())["count"] == 4
    with pytest.raises(SimError, match="describes a different dataset"):
        init_dataset(root, DatasetSpec(width=16, height=8, visibility=True, seed=5), 4)


def test_a_resume_without_the_oracle_keeps_what_it_measured(tmp_path: Path) -> None:
    """A set rendered with `--visibility` and resumed without it to a larger count wrote the new manifest without the
    oracle's summary (the manifest's `visibility`), though its samples keep their records: the summary of what was
    measured (`n` per type) stays until a render with the oracle writes it again."""
    root = tmp_path / "set"
    init_dataset(root, DatasetSpec(width=16, height=8, visibility=True), 2)
    path = root / "manifest.json"
    manifest = json.loads(path.read_text())
    manifest["visibility"] = {"threshold_snr": 1.0, "by_type": {"dent": {"n": 1}}}
    path.write_text(json.dumps(manifest))
    init_dataset(root, DatasetSpec(width=16, height=8), 4)
    after = json.loads(path.read_text())
    assert after["count"] == 4
    assert after["visibility"] == manifest["visibility"]
