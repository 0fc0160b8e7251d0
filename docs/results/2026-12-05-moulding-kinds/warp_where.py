"""Where the shipped window finds a warped part (validation only: data/warp-val-1199, screen-plan.md's set): the column
and row of each part's highest window z, for the 40 highest-scoring warped and the 40 highest-scoring good parts, in the
model's input (96 x 192; the part's region spans columns 8-182). Run from the repository's root:
python docs/results/2026-12-05-moulding-kinds/warp_where.py > docs/results/2026-12-05-moulding-kinds/where.txt"""

import itertools

import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

MODEL = "model/weights/default"
COLUMNS = [0, 40, 80, 120, 150, 170, 192]
ROWS = [0, 24, 48, 72, 96]


def bins(edges: list[int]) -> list[str]:
    return [f"{a}-{b - 1}" for a, b in itertools.pairwise(edges)]


def main() -> None:
    ck = load_checkpoint(MODEL)
    vm = ck.detector.variation
    s = model_split(ck, MODEL, "data/warp-val-1199", "val")
    label = np.asarray(s.label)
    out = vm.zmaps(s.priors)
    maps, scores = out.maps.numpy(), out.scores.numpy()
    region = vm.region.numpy()
    cols, rows = np.flatnonzero(region.any(0)), np.flatnonzero(region.any(1))
    print(f"part region: columns {cols.min()}-{cols.max()}, rows {rows.min()}-{rows.max()}")
    for name, sel in (("warped", label == 1), ("good", label == 0)):
        idx = np.flatnonzero(sel)
        top = idx[np.argsort(-scores[idx])][:40]
        at = np.array([np.unravel_index(np.argmax(maps[i]), maps[i].shape) for i in top])
        by_col = np.histogram(at[:, 1], COLUMNS)[0].tolist()
        by_row = np.histogram(at[:, 0], ROWS)[0].tolist()
        print(f"{name}: {sel.sum()} parts; the 40 highest: median window z {np.median(scores[top]):.2f}; their maxima "
              f"by column {dict(zip(bins(COLUMNS), by_col, strict=True))}, "
              f"by row {dict(zip(bins(ROWS), by_row, strict=True))}")


if __name__ == "__main__":
    main()
