"""plan.md, development screen: the outline check's score from cached edge rows (rows.py), per run length, on the
development sets only. Fit: the good training parts (ef-train); threshold: the largest score of the good calibration
parts (ef-val); read: flash-dev-1201 (caught by edge and width, alone and with the shipped file's decision), the good
parts of pv-val, warp-val and flash-dev (rejected beyond the calibration). Run from the repository's root:
python docs/results/2026-12-05-outline/screen.py"""

from __future__ import annotations

import csv
import json
from collections import defaultdict

import numpy as np

from sim.dataset import sample_dir

RUNS = (4, 8, 16)
FLOOR = 0.02
"""A run's spread is floored at this (input px)."""


def load(name: str) -> dict:
    d = np.load(f"runs/outline/rows-{name}.npz")
    return {k: d[k] for k in d.files}


def detrend(rows: np.ndarray) -> np.ndarray:
    """(N, E, W) edge rows -> each part's edge minus its robust parabola (the shape check's two fits)."""
    u = np.linspace(-1.0, 1.0, rows.shape[-1])
    out = np.full(rows.shape, np.nan)
    for i in np.ndindex(rows.shape[:-1]):
        y = rows[i]
        k = np.isfinite(y)
        if k.sum() < 10:
            continue
        p = np.polyfit(u[k], y[k], 2)
        off = np.abs(y - np.polyval(p, u))
        k &= off <= 3 * max(float(np.nanmedian(off)) / 0.6745, 1e-3)
        if k.sum() >= 10:
            p = np.polyfit(u[k], y[k], 2)
        out[i] = y - np.polyval(p, u)
    return out


def runs(d: np.ndarray, length: int) -> np.ndarray:
    """(N, E, W) -> (N, E, W - length + 1) mean over each run of ``length`` columns (NaN columns read as 0)."""
    c = np.cumsum(np.nan_to_num(np.concatenate([np.zeros((*d.shape[:-1], 1)), d], -1)), -1)
    return (c[..., length:] - c[..., :-length]) / length


class Check:
    def __init__(self, train: np.ndarray, length: int) -> None:
        d = detrend(train)
        self.median = np.nanmedian(d, 0)
        self.length = length
        r = runs(d - self.median, length)
        self.centre = np.median(r, 0)
        self.spread = np.maximum(1.4826 * np.median(np.abs(r - self.centre), 0), FLOOR)

    def z(self, rows: np.ndarray) -> np.ndarray:
        """(N, E, W') signed run z."""
        return (runs(detrend(rows) - self.median, self.length) - self.centre) / self.spread

    def score(self, rows: np.ndarray, edges: tuple[int, ...] = (0, 1)) -> np.ndarray:
        return np.abs(self.z(rows)[:, list(edges)]).max((1, 2))


def shipped_caught() -> dict[int, bool]:
    ev = json.load(open("runs/outline/eval-dev/eval.json"))
    with open("runs/outline/eval-dev/scores.csv") as f:
        return {int(r["index"]): float(r["score"]) > ev["threshold"] for r in csv.DictReader(f)}


def main() -> None:
    train, cal = load("ef-train"), load("ef-val")
    sets = {n: load(n) for n in ("flash-dev", "pv-val", "warp-val")}
    shipped = shipped_caught()
    dev = sets["flash-dev"]
    params = [json.loads((sample_dir("data/flash-dev-1201", int(i)) / "params.json").read_text()).get("defect")
              for i in dev["index"]]
    for length in RUNS:
        for edges in ((0, 1), (1,), (0,)):
            ck = Check(train["rows"], length)
            thr = float(ck.score(cal["rows"], edges).max())
            line = [f"L={length:2d} edges={edges}: threshold {thr:6.2f}"]
            for n in ("pv-val", "warp-val", "flash-dev"):
                s = sets[n]
                good = s["label"] == 0
                line.append(f"{n} good {int((ck.score(s['rows'][good], edges) > thr).sum())}/{int(good.sum())}")
            sc = ck.score(dev["rows"], edges)
            groups: dict[str, list[int]] = defaultdict(lambda: [0, 0, 0])
            for i, (p, lab) in enumerate(zip(params, dev["label"], strict=True)):
                if lab != 1 or p is None:
                    continue
                w = "0.2-0.4" if p["width_mm"] < 0.4 else "0.4-0.7" if p["width_mm"] < 0.7 else "0.7-1.0"
                face = "end" if abs(p["normal"][1]) < 0.5 else "front"
                for key in ("all", f"{face} {p['edge']}", f"{face} {p['edge']} {w}"):
                    g = groups[key]
                    g[0] += sc[i] > thr
                    g[1] += shipped[int(dev["index"][i])] or sc[i] > thr
                    g[2] += 1
            print("; ".join(line))
            for key in sorted(groups):
                c, both, n = groups[key]
                print(f"    {key:24s} check {c:3d}/{n:3d}  shipped+check {both:3d}/{n:3d}")


if __name__ == "__main__":
    main()
