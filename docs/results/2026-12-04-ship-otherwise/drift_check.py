"""After the reads (not in the plan): what the station's drift monitor says on seed 1196's frames as built and with
the unstated 256-code pedestal, against the shipped file's recorded training range (its default window).

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-04-ship-otherwise/drift_check.py > .../drift-check.txt
"""
import json
from pathlib import Path

import cv2
import numpy as np

from model.priors.api import compute_priors
from model.priors.frame_stats import frame_statistics
from model.priors.sensor_correction import SensorCorrection
from station.drift import DriftMonitor, trained_range

FRAMES = 120


def main() -> None:
    trained = trained_range(json.loads(Path("model/weights/default.json").read_text()))
    print(f"trained: {trained.describe()}\n")
    for name in ("so-built-1196", "so-pedestal256-1196", "so-pedestal256bl-1196", "so-camera-1196"):
        root = Path("data") / name
        level = json.loads((root / "manifest.json").read_text()).get("black_level", 0)
        mon, stats, said, correct = DriftMonitor(trained), [], [], SensorCorrection.of(level)
        for i, f in enumerate(sorted(root.glob("samples/*/raw.png"))[:FRAMES]):
            raw = correct(cv2.imread(str(f), cv2.IMREAD_UNCHANGED), 12)  # the station's removal of a stated level
            st = frame_statistics(compute_priors(raw, priors=("intensity", "dolp"), bit_depth=12), raw=raw,
                                  bit_depth=12)
            stats.append(st.median_level)
            if text := mon.update(st):
                said.append(f"frame {i + 1}: {text}")
        print(f"{name} (black level stated: {level}): median_level over frames {np.median(stats):.3f}")
        print("\n".join(f"  {s}" for s in said) or "  no warning", "\n")


if __name__ == "__main__":
    main()
