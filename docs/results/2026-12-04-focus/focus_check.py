"""plan.md's reading 2: the candidate ``edge_level`` (``model.priors.frame_stats.edge_level``) on the shipped file's
375 training frames (its trained quartiles), then through the drift monitor's rule (a window of 50, from the 10th
frame: the window's median against the quartiles widened by half the interquartile range, at least 0.005) on the
first 120 frames of each set. Frames read as the station reads them (a stated black level removed by its
``SensorCorrection``).

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-04-focus/focus_check.py > .../focus-check.txt
"""
import json
from pathlib import Path

import cv2
import numpy as np
from tqdm import tqdm

from model.priors.api import compute_priors
from model.priors.frame_stats import edge_level
from model.priors.sensor_correction import SensorCorrection
from sim.dataset import open_dataset

FRAMES, WINDOW, MIN_FRAMES, MARGIN, FLOOR = 120, 50, 10, 0.5, 0.005
BLURRED = [("fo-blur10-1196", "lens blur 1.0 px"), ("fo-blur15-1196", "lens blur 1.5 px"),
           ("fo-blur20-1196", "lens blur 2.0 px")]
REPORTED = [("so-blurff-1196", "lens blur 0.7 px"), ("so-motion2-1196", "moving 2 px"),
            ("so-motion4-1196", "moving 4 px")]
SHARP = [("so-built-1196", "seed 1196 as built"), ("so-chamfer03-1196", "chamfered 0.3 mm"),
         ("so-round03-1196", "rounded 0.3 mm"), ("so-pedestal256bl-1196", "256-code pedestal, stated"),
         ("so-hot30-1196", "30 hot pixels"), ("sim-demo-line-panel", "the demo set"), ("ir-ggx-1193", "GGX lobe"),
         ("ir-rough-1193", "duller finish"), ("new-kinds-heldout-1195", "new kinds"),
         ("line-pv-val", "the validation set")]


def edge_of(raw: np.ndarray, bits: int) -> float:
    return edge_level(compute_priors(raw, priors=("intensity",), bit_depth=bits)["intensity"])


def trained() -> np.ndarray:
    ds = open_dataset("data/line-ef-train")
    bits = ds.manifest.get("bit_depth")
    out = []
    for i in tqdm(ds.indices("train"), desc="training frames", unit="frame"):
        s = ds.load(i)
        if not s.label:
            out.append(edge_of(s.raws[0], bits))
    return np.array(out)


def main() -> None:
    train = trained()
    q1, q3 = np.percentile(train, (25, 75))
    tol = max(MARGIN * (q3 - q1), FLOOR)
    lo, hi = q1 - tol, q3 + tol
    print(f"trained: {len(train)} frames, edge_level median {np.median(train):.4f}, quartiles {q1:.4f}..{q3:.4f}, "
          f"2-98 % {np.percentile(train, 2):.4f}..{np.percentile(train, 98):.4f}; bounds {lo:.4f}..{hi:.4f}\n")
    for group, sets in (("blurred (bar 1: must warn)", BLURRED), ("reported", REPORTED),
                        ("sharp (bar 2: must stay quiet)", SHARP)):
        print(f"## {group}")
        for name, what in sets:
            root = Path("data") / name
            manifest = json.loads((root / "manifest.json").read_text())
            bits, correct = manifest.get("bit_depth", 12), SensorCorrection.of(manifest.get("black_level") or 0)
            values, first, warned = [], None, 0
            for i, f in enumerate(sorted(root.glob("samples/*/raw.png"))[:FRAMES]):
                values.append(edge_of(correct(cv2.imread(str(f), cv2.IMREAD_UNCHANGED), bits), bits))
                if len(values) >= MIN_FRAMES:
                    med = float(np.median(values[-WINDOW:]))
                    if med < lo or med > hi:
                        warned += 1
                        first = first or i + 1
            side = "" if first is None else (" low" if np.median(values[-WINDOW:]) < lo else " high")
            print(f"{what:28s} {name:24s} frames {len(values):3d}  median {np.median(values):.4f}  "
                  + (f"warns{side} from frame {first}, in {warned} of {len(values) - MIN_FRAMES + 1} windows"
                     if first else "no warning"))
        print()


if __name__ == "__main__":
    main()
