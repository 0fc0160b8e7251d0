"""plan.md, development: each part's two long edges in its registered intensity, per column to a fraction of a
pixel, cached for the screen (screen.py). The edges: the front face's bottom edge (the shape check's, over the body's
straight run untrimmed) and the strongest straight edge 12-40 rows above it along the same columns (the front face's
top edge), found in the shipped file's reference. Writes runs/outline/rows-NAME.npz: rows (N, 2, W) (NaN where a
column shows no edge), label (N,), index (N,). Run from the repository's root:
python docs/results/2026-12-05-outline/rows.py NAME DATA SPLIT [good]"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.shape_check import robust_line, vertical_change
from station.evaluation import model_split

MODEL = "model/weights/default"
SEARCH = 3


def edges(vm) -> tuple[np.ndarray, list[tuple[np.ndarray, float]]]:
    """The columns and, per edge, its reference rows per column (straight line) and the sign of its change."""
    region, change = vm.region.numpy(), vertical_change(vm.reference.numpy())
    first, end, row0, slope, sign = (float(v) for v in vm.shape.edge)
    run = round((end - first) / 0.8)  # the untrimmed run: trimmed by 10 % each end
    lo_c = int(first - 0.1 * run) + 2
    hi_c = int(end + 0.1 * run) - 2
    cols = np.arange(lo_c, hi_c)
    bottom = row0 + slope * cols
    out = [(bottom, sign)]
    rows = []
    for c, b in zip(cols, bottom, strict=True):
        lo, hi = int(b) - 40, int(b) - 12
        rows.append(lo + int(np.argmax(np.abs(change[lo:hi, c]))))
    p, _ = robust_line(cols.astype(float), np.asarray(rows, float), 1.5)
    top = np.polyval(p, cols)
    at = np.rint(top).astype(int)
    out.append((top, float(np.sign(np.sum(change[at, cols])))))
    assert region[at, cols].all()
    return cols, out


def edge_rows(intensity: np.ndarray, cols: np.ndarray, line: np.ndarray, sign: float) -> np.ndarray:
    """Per column, the sub-pixel row of the strongest ``sign`` change within SEARCH of ``line``."""
    change = sign * vertical_change(intensity)
    out = np.full(len(cols), np.nan)
    for i, (c, ln) in enumerate(zip(cols, line, strict=True)):
        ln = round(ln)
        lo, hi = max(ln - SEARCH, 1), min(ln + SEARCH + 1, change.shape[0] - 1)
        r = lo + int(np.argmax(change[lo:hi, c]))
        a, b, d = change[r - 1, c], change[r, c], change[r + 1, c]
        den = a - 2 * b + d
        if b > 0:
            out[i] = r + (0.5 * (a - d) / den if den < 0 else 0.0)
    return out


def main() -> None:
    name, data, split = sys.argv[1:4]
    good_only = len(sys.argv) > 4
    ck = load_checkpoint(MODEL)
    vm = ck.detector.variation
    cols, lines = edges(vm)
    sp = model_split(ck, MODEL, data, split, good_only=good_only)
    rows = []
    for x in sp.priors.numpy():
        inten = vm._aligned(x)[0][vm.intensity]
        rows.append([edge_rows(inten, cols, ln, s) for ln, s in lines])
    Path("runs/outline").mkdir(parents=True, exist_ok=True)
    np.savez(f"runs/outline/rows-{name}.npz", rows=np.asarray(rows), label=np.asarray(sp.label),
             index=np.asarray(sp.index) if hasattr(sp, "index") else np.arange(len(rows)), cols=cols,
             lines=np.asarray([ln for ln, _ in lines]))
    print(name, len(rows), "parts; columns", cols[0], "-", cols[-1], "; edges at rows",
          [round(float(ln[len(ln) // 2]), 1) for ln, _ in lines])


if __name__ == "__main__":
    main()
