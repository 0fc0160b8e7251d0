"""Check 67's figure: the line camera's first four front-face misses on seed 1167 (dents and scratches, in index
order: a rule fixed before any score of the check was read), each from the line camera and from the side camera
under its flat dome: the frame's intensity (demosaiced from the raw mosaic, as the station computes it) around the
defect, its mask outlined.

Usage (repository root): python docs/results/2026-11-30-side-view/figure67.py LINE_EVAL OUT.png
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "2026-11-30-front-view"))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "2026-11-27-bright-field"))
from faces import faces_of
from figure66 import frame_maps, show

from sim.dataset import Dataset
from station.eval_compare import read_report

SETS = {"line camera": "data/line-panel-heldout-1167", "side camera, flat dome": "data/sv-heldout-1167"}
SHOWN = 4


def misses(line_eval: str) -> list[int]:
    """The line camera's front-face dents and scratches at or under its threshold, first ``SHOWN`` by index."""
    scores, groups = faces_of(line_eval, SETS["line camera"])
    threshold = float(read_report(line_eval)["threshold"])
    return sorted(i for i, (kind, face) in groups.items()
                  if face == "front" and kind in ("dent", "scratch") and scores[i] <= threshold)[:SHOWN]


def main() -> None:
    line_eval, out = sys.argv[1:3]
    parts = misses(line_eval)
    sets = {name: Dataset(root) for name, root in SETS.items()}
    fig, ax = plt.subplots(len(parts), len(sets), figsize=(6, 2.6 * len(parts)), squeeze=False)
    for r, i in enumerate(parts):
        for c, (name, ds) in enumerate(sets.items()):
            sample = ds.load(i)
            intensity, _ = frame_maps(sample, ds.manifest["bit_depth"])
            show(ax[r, c], intensity, sample.defect_mask > 0,
                 f"{i} {(sample.params['defect'] or {}).get('type', '')}: {name}", cmap="gray", vmin=0, vmax=1)
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main()
