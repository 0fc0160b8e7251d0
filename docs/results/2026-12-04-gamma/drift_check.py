"""plan.md's reading 2: the station's drift monitor (the shipped file's recorded range, its default window) on the
first 120 frames of seed 1196 as built and through each gamma: every warning it gives, with the frame it came at.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-04-gamma/drift_check.py > .../drift-check.txt
"""
import json
from pathlib import Path

import cv2
import numpy as np

from model.priors.api import compute_priors
from model.priors.frame_stats import frame_statistics
from station.drift import DriftMonitor, trained_range

FRAMES = 120


def main() -> None:
    trained = trained_range(json.loads(Path("model/weights/default.json").read_text()))
    print(f"trained: {trained.describe()}\n")
    for name in ("so-built-1196", "ga-g08-1196", "ga-g125-1196"):
        mon, stats, said = DriftMonitor(trained), [], []
        for i, f in enumerate(sorted((Path("data") / name).glob("samples/*/raw.png"))[:FRAMES]):
            raw = cv2.imread(str(f), cv2.IMREAD_UNCHANGED)
            st = frame_statistics(compute_priors(raw, priors=("intensity", "dolp"), bit_depth=12), raw=raw,
                                  bit_depth=12, stride=3)  # as the station reads them
            stats.append(st)
            if text := mon.update(st):
                said.append(f"frame {i + 1}: {text}")
        medians = ", ".join(f"{k} {np.median([getattr(s, k) for s in stats]):.3f}"
                            for k in ("median_level", "high_level", "dark_level", "dolp_level", "edge_level"))
        print(f"{name}: over frames {medians}")
        print("\n".join(f"  {s}" for s in said) or "  no warning", "\n")


if __name__ == "__main__":
    main()
