"""`make side-model` (scripts/make-side-model.sh): dry-run with a `station` and a `python` that only record their
arguments, it renders the side camera's twins of make-model.sh's sets (edges drawn where it draws them), fits from
the shipped line file's networks, thresholds with the side camera's presence rule and splits the two thresholds on the
validation twins."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SIDE = "sim/presets/side-view.toml"


def test_make_side_model_renders_twins_and_splits_on_them(tmp_path: Path) -> None:
    calls = tmp_path / "calls"
    stub = tmp_path / "bin"
    stub.mkdir()
    for name in ("station", "python"):
        (stub / name).write_text(f'#!/bin/sh\necho "{name} $*" >> {calls}\n')
        (stub / name).chmod(0o755)
    runs = tmp_path / "runs"
    env = {**os.environ, "BIN": str(stub), "RUNS": str(runs)}
    subprocess.run(["bash", str(ROOT / "scripts" / "make-side-model.sh")], env=env, check=True, capture_output=True)
    lines = [line.split() for line in calls.read_text().splitlines()]
    renders = [a for a in lines if a[:2] == ["station", "render"]]

    def out(a: list[str]) -> str:
        return a[a.index("--out") + 1]

    def configs(a: list[str]) -> list[str]:
        return [a[i + 1] for i, x in enumerate(a) if x == "--config"]

    assert {out(a) for a in renders} == {"data/sw-train", "data/sw-pf-val", "data/sw-pv-val", "data/line-pv-val"}
    for a in renders:  # the side camera's preset last on its sets, absent from the line camera's
        assert (configs(a)[-1] == SIDE) == (out(a) != "data/line-pv-val")
        seed = a[a.index("--seed") + 1]
        assert seed == ("101" if out(a) == "data/sw-train" else "303")  # make-model.sh's seeds: twins of its sets
    for a in renders:  # each part's chamfer drawn 0-0.4 mm where make-model.sh draws it (rule 67): training and
        drawn = a[a.index("--edge-mm") + 1] if "--edge-mm" in a else None  # calibration; validation as built
        assert drawn == ("0,0.4" if out(a) in ("data/sw-train", "data/sw-pf-val") else None)
    train_shards = sorted(int(a[a.index("--shard") + 1].split("/")[0]) for a in renders if out(a) == "data/sw-train")
    assert train_shards == [3, 4, 5, 6, 7, 8, 9, 13, 14, 15, 16, 17, 18, 19]  # the train split only
    source = next(a for a in lines if a[0] == "python")  # the shipped line file's networks, look and fit dropped
    assert "networks_only" in " ".join(source) and source[-2:] == ["model/weights/default", f"{runs}/source/default"]
    steps = [a[1] for a in lines if a[0] == "station" and a[1] != "render"]
    assert steps == ["variation", "residual", "threshold", "split"]
    variation, residual, threshold, split = (next(a for a in lines if a[1] == s) for s in steps)
    assert variation[variation.index("--model") + 1] == f"{runs}/source/default" and "--refit" in variation
    assert "--second-look" in residual and threshold[threshold.index("--presence-rule") + 1] == "row_contrast"
    assert threshold[threshold.index("--data") + 1] == "data/sw-pv-val"
    assert (split[split.index("--data") + 1], split[split.index("--second-data") + 1]) == ("data/line-pv-val",
                                                                                          "data/sw-pv-val")
    assert split[split.index("--second-model") + 1] == f"{runs}/side"
