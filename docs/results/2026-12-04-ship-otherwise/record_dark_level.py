"""After the reads: record the darkest-pixel statistic (``dark_level``, ``model.priors.frame_stats``) in a file's
trained range, recomputed from the frames ``station train`` recorded it from (the training set's good parts of its
train split), and check the recorded statistics come out as they were.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-04-ship-otherwise/record_dark_level.py \
        model/weights/default data/line-ef-train
"""
import json
import sys
from pathlib import Path

from tqdm import tqdm

from model.priors.api import compute_set_priors
from model.priors.frame_stats import StatisticsRange, frame_statistics
from sim.dataset import open_dataset


def main(model: str, data: str) -> None:
    sidecar = Path(model + ".json")
    meta = json.loads(sidecar.read_text())
    before = meta["train"]["frame_statistics"]
    ds = open_dataset(data)
    stats = []
    for i in tqdm(ds.indices("train"), desc="frames", unit="frame"):
        s = ds.load(i)
        if s.label:
            continue
        maps = compute_set_priors(s.raws, ds.dome_segments, ds.manifest.get("layout", "imx250mzr"),
                                  priors=("intensity", "dolp"), bit_depth=ds.manifest.get("bit_depth"))
        stats.append(frame_statistics(dict(maps), raw=s.raws[0], bit_depth=ds.manifest.get("bit_depth")))
    after = StatisticsRange.from_frames(stats).to_dict()
    assert after["n_frames"] == before["n_frames"], (after["n_frames"], before["n_frames"])
    for key in StatisticsRange.KEYS:
        for name, v in before[key].items():
            assert abs(after[key][name] - v) <= 1e-6 * max(1.0, abs(v)), (key, name, after[key][name], v)
    meta["train"]["frame_statistics"] = after
    sidecar.write_text(json.dumps(meta, indent=1))
    print(f"{sidecar}: the {after['n_frames']} frames' recorded statistics match; dark_level "
          + ", ".join(f"{k} {after[k]['dark_level']:.4f}" for k in StatisticsRange.KEYS))


if __name__ == "__main__":
    main(*sys.argv[1:3])
