"""shape-plan.md: a bow measured as the sag of the part's edges in the registered intensity, alone and beside the
shipped window, on validation sets only. Calibration as broad_screen.py: the window's per-pixel median / 95th
percentile from the even good parts of VAL's val split (A); each score over its A 99th percentile; thresholds at 1 %
from the odd good parts (B). Writes OUT.json; prints a table.

The edges: the top face's front edge and the part's bottom edge, the two edges along the body that no stud breaks
(rows 45-70 and 75-93 of the 96 x 192 input, columns 15-130: the body, the plug and the ends left out), found in the
registered reference as the row of the strongest vertical change per column. In each part, per column, the row of
the strongest change of the same sign within +-3 rows of the reference's, to a fraction of a pixel (a parabola through
the peak and its neighbours); over the columns a line and a parabola are fitted, and the parabola's coefficient is
the edge's sag (input px: its middle against the chord through its ends, sign flipped). The part's sag is the mean
of the two edges'; its score, |sag - median(A)| over A's median absolute deviation.

Usage (from the repository's root): python shape_screen.py MODEL VAL WARP OUT.json"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

import cv2
import numpy as np
from broad_screen import SHIFTS, row_of, stats

from model.draem.checkpoint import load_checkpoint
from model.draem.shifts import Channels, shift
from model.draem.variation import NOISE_CAP, WINDOW_BLUR_PX, WINDOW_QUANTILE
from station.evaluation import model_split

EDGE_ROWS = ((45, 70), (75, 93))
COLUMNS = (15, 131)
SEARCH = 3
EDGES = tuple(int(e) for e in os.environ.get("EDGES", "0,1").split(","))
"""Which of EDGE_ROWS to measure (variant 2b: EDGES=1, the bottom edge alone, with ROBUST=1)."""
ROBUST = os.environ.get("ROBUST", "0") == "1"
"""Variant 2b: the reference's edge as a straight line fitted to its rows (columns off it by over 1.5 px dropped),
the search around that line; each part's parabola fitted again without the columns off the first fit by over 3
robust spreads."""


def vertical_change(image: np.ndarray) -> np.ndarray:
    """(H, W) -> (H - 1, W): the row-to-row change of the image smoothed at sigma 1 px (row r: between r and r + 1)."""
    return np.diff(cv2.GaussianBlur(image.astype(np.float32), (0, 0), 1.0), axis=0)


def edge_rows(change: np.ndarray, guide: np.ndarray, sign: np.ndarray) -> np.ndarray:
    """Per column of COLUMNS, the sub-pixel row of the largest ``sign``-signed change within SEARCH of ``guide``."""
    rows = []
    for i, c in enumerate(range(*COLUMNS)):
        lo, hi = max(int(guide[i]) - SEARCH, 1), min(int(guide[i]) + SEARCH + 1, change.shape[0] - 1)
        col = sign[i] * change[:, c]
        r = lo + int(np.argmax(col[lo:hi]))
        a, b, d = col[r - 1], col[r], col[r + 1]
        den = a - 2 * b + d
        rows.append(r + (0.5 * (a - d) / den if den < 0 else 0.0))
    return np.asarray(rows)


def sag(rows: np.ndarray) -> float:
    """The parabola's coefficient over the columns mapped to [-1, 1], sign flipped: + when the middle lies above the
    chord through the ends (fewer rows), in input px. With ROBUST, fitted again without the columns off the first fit
    by over 3 robust spreads."""
    u = np.linspace(-1.0, 1.0, len(rows))
    p = np.polyfit(u, rows, 2)
    if ROBUST:
        off = np.abs(rows - np.polyval(p, u))
        keep = off <= 3 * max(float(np.median(off)) / 0.6745, 1e-3)
        p = np.polyfit(u[keep], rows[keep], 2)
    return -float(p[0])


def straight(guide: np.ndarray) -> np.ndarray:
    """ROBUST: the reference's edge rows as a straight line, fitted without the columns off a first fit by 1.5 px."""
    c = np.arange(len(guide), dtype=float)
    p = np.polyfit(c, guide, 1)
    keep = np.abs(guide - np.polyval(p, c)) <= 1.5
    return np.rint(np.polyval(np.polyfit(c[keep], guide[keep], 1), c)).astype(int)


def main() -> None:
    model, val, warp, out = sys.argv[1:]
    ck = load_checkpoint(model)
    vm = ck.detector.variation
    region = vm.scored_region()
    ref_change = vertical_change(vm.reference.numpy())
    guides, signs = [], []
    for lo, hi in (EDGE_ROWS[e] for e in EDGES):
        band = ref_change[lo:hi, COLUMNS[0]:COLUMNS[1]]
        guide = lo + np.argmax(np.abs(band), 0)
        guides.append(straight(guide) if ROBUST else guide)
        signs.append(np.sign(band[np.argmax(np.abs(band), 0), np.arange(band.shape[1])]))

    def measure(priors: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """-> (N,) the part's sag, (N, H, W) its log3 window map, (N, H, W) its judged pixels."""
        sags, maps, judged = [], [], []
        for x in priors:
            warped, _ = vm._registered(x, vm.region.numpy())
            change = vertical_change(warped[vm.intensity])
            sags.append(np.mean([sag(edge_rows(change, g, s)) for g, s in zip(guides, signs, strict=True)]))
            r, coef, j, _ = vm._judged_residual(x)
            z = vm.used(vm.clustered(r, coef))
            level = vm.noise_level(np.abs(z), j)
            z = (np.nan_to_num(z / (level if 1.0 < level <= NOISE_CAP else 1.0)) * j).astype(np.float32)
            maps.append(stats(z)["log3"])
            judged.append(j)
        return np.asarray(sags), np.stack(maps), np.stack(judged)

    v = model_split(ck, model, val, "val")
    vx, vl, vt = v.priors.numpy(), np.asarray(v.label), np.array(v.defect_type)
    vsag, vmap, vj = measure(vx)
    good = np.flatnonzero(vl == 0)
    A, B = good[0::2], good[1::2]
    loc = np.median(vmap[A], 0)
    spread = cv2.GaussianBlur(np.percentile(vmap[A], WINDOW_QUANTILE, 0) - loc, (0, 0), WINDOW_BLUR_PX)
    spread = np.maximum(spread, max(float(np.percentile(spread[region], 5.0)), 1e-3))
    centre = float(np.median(vsag[A]))
    mad = float(np.median(np.abs(vsag[A] - centre))) / 0.6745

    def scores(sags: np.ndarray, maps: np.ndarray, judged: np.ndarray) -> dict[str, np.ndarray]:
        w = (np.maximum((maps - loc) / spread, 0) * (region & judged)).reshape(len(maps), -1).max(1)
        return {"log3": w, "sag": np.abs(sags - centre) / mad}

    vs = scores(vsag, vmap, vj)
    norm = {k: float(np.percentile(s[A], 99)) for k, s in vs.items()}
    combos = (("log3",), ("sag",), ("log3", "sag"))

    def combined(sc: dict[str, np.ndarray], combo: tuple[str, ...]) -> np.ndarray:
        return np.max([sc[k] / norm[k] for k in combo], 0)

    w = model_split(ck, model, warp, "val")
    wl = np.asarray(w.label)
    wsag, wmap, wj = measure(w.priors.numpy())
    ws = scores(wsag, wmap, wj)
    sag_mm = [abs((json.loads((Path(warp) / "samples" / f"{i:06d}" / "params.json").read_text()).get("defect") or {})
                  .get("sag_mm", 0.0)) for i in w.index]
    ch = Channels.of(tuple(ck.detector.config.priors))
    measured = {n: measure(shift(n, vx[B], ch)) for n in SHIFTS}
    shifted = {n: scores(*m) for n, m in measured.items()}
    rows = {"+".join(c): row_of(combined(vs, c), combined(ws, c), {n: combined(m, c) for n, m in shifted.items()},
                                float(np.percentile(combined(vs, c)[B], 99)), vl, vt, B, wl, "+".join(c), 10)
            for c in combos}
    off = np.abs(wsag - centre)
    print(f"sag on A's good parts: median {centre:.4f} input px, robust spread {mad:.4f}; seed 1199: median |sag - "
          f"median| {np.median(off[wl == 1]):.3f} on warped parts, {np.median(off[wl == 0]):.3f} on good ones")
    json.dump({"sag_centre_px": centre, "sag_spread_px": mad, "norm": norm, "B": len(B), "rows": rows,
               "warp_sags_px": wsag.tolist(), "warp_labels": wl.tolist(), "val_sags_px": vsag.tolist(),
               "val_labels": vl.tolist(), "val_types": vt.tolist(), "val_log3": vs["log3"].tolist(),
               "warp_log3": ws["log3"].tolist(), "A": A.tolist(), "B_parts": B.tolist(),
               "shifted_B": {n: {"sags_px": m[0].tolist(), "log3": shifted[n]["log3"].tolist()}
                             for n, m in measured.items()},
               "sag_mm": sag_mm}, open(out, "w"), indent=1)


if __name__ == "__main__":
    main()
