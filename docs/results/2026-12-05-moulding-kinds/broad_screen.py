"""screen-plan.md: a broad window (the signed z smoothed at a large scale) beside the shipped curvature window, on
validation sets only. Calibration as ../2026-11-29-ridge/window_screen.py (stop 60): per-pixel median / 95th
percentile of each statistic from the even good parts of VAL's val split (A), scores over their A 99th percentile,
thresholds at 1 % from its odd good parts (B). Scored on B and VAL's defective parts, on WARP's val split, and on B's
good parts under three frame shifts. Writes OUT.json; prints a table.

Usage (from the repository's root): python broad_screen.py MODEL VAL WARP OUT.json"""

from __future__ import annotations

import json
import sys

import cv2
import numpy as np
from scipy.ndimage import gaussian_filter

from model.draem.checkpoint import load_checkpoint
from model.draem.metrics import auroc
from model.draem.shifts import Channels, shift
from model.draem.variation import NOISE_CAP, WINDOW_BLUR_PX, WINDOW_QUANTILE
from station.evaluation import model_split

SHIFTS = ("gamma 1.25", "exposure x1.3", "blur 0.5 px")
COMBOS = (("log3",), ("smooth6",), ("smooth12",), ("log3", "smooth6"), ("log3", "smooth12"))


def stats(z: np.ndarray) -> dict[str, np.ndarray]:
    """(C, H, W) signed z, zero outside the judged pixels -> each statistic's (H, W) map."""
    out = {"log3": 9.0 * np.max([np.abs(gaussian_filter(zc, 3, order=(2, 0)) + gaussian_filter(zc, 3, order=(0, 2)))
                                 for zc in z], 0)}
    for s in (6, 12):
        out[f"smooth{s}"] = s * np.max([np.abs(gaussian_filter(zc, s)) for zc in z], 0)
    return out


def row_of(val: np.ndarray, warp: np.ndarray, shifted: dict[str, np.ndarray], t: float, vl: np.ndarray,
           vt: np.ndarray, B: np.ndarray, wl: np.ndarray, name: str = "", width: int = 16) -> dict[str, float]:
    """One window's (or combination's) row at threshold ``t``: VAL's scores ``val`` (labels ``vl``, types ``vt``, its
    odd good parts ``B``), WARP's ``warp`` (labels ``wl``), B's under each shift; printed as NAME (``width`` wide)."""
    keep = (vl == 1) | np.isin(np.arange(len(vl)), B)
    row = {"five kinds caught": float((val[vl == 1] > t).mean()), "val B good rejected": float((val[B] > t).mean()),
           "five kinds AUROC": auroc(vl[keep], val[keep])}
    for d in sorted(set(vt) - {""}):
        row[d] = float((val[vt == d] > t).mean())
    row["warps caught"] = float((warp[wl == 1] > t).mean())
    row["warp val good rejected"] = float((warp[wl == 0] > t).mean())
    row["warps AUROC"] = auroc(wl, warp)
    for n, s in shifted.items():
        row[f"B good rejected, {n}"] = float((s > t).mean())
    print(f"{name:{width}s}", json.dumps({k: round(x, 3) for k, x in row.items()}), flush=True)
    return row


def main() -> None:
    model, val, warp, out = sys.argv[1:]
    ck = load_checkpoint(model)
    vm = ck.detector.variation
    region = vm.scored_region()

    def maps_of(priors: np.ndarray) -> tuple[dict[str, np.ndarray], np.ndarray]:
        maps, judged = {}, []
        for x in priors:
            r, coef, j, _ = vm._judged_residual(x)
            z = vm.used(vm.clustered(r, coef))
            level = vm.noise_level(np.abs(z), j)
            z = (np.nan_to_num(z / (level if 1.0 < level <= NOISE_CAP else 1.0)) * j).astype(np.float32)
            judged.append(j)
            for k, v in stats(z).items():
                maps.setdefault(k, []).append(v.astype(np.float32))
        return {k: np.stack(v) for k, v in maps.items()}, np.stack(judged)

    v = model_split(ck, model, val, "val")
    vx, vl, vt = v.priors.numpy(), np.asarray(v.label), np.array(v.defect_type)
    vmaps, vj = maps_of(vx)
    print(f"{val}: {len(vl)} parts", flush=True)
    good = np.flatnonzero(vl == 0)
    A, B = good[0::2], good[1::2]
    cal = {}
    for k, w in vmaps.items():
        loc = np.median(w[A], 0)
        spread = cv2.GaussianBlur(np.percentile(w[A], WINDOW_QUANTILE, 0) - loc, (0, 0), WINDOW_BLUR_PX)
        cal[k] = (loc, np.maximum(spread, max(float(np.percentile(spread[region], 5.0)), 1e-3)))

    def scores(maps: dict[str, np.ndarray], judged: np.ndarray) -> dict[str, np.ndarray]:
        return {k: (np.maximum((maps[k] - loc) / spread, 0) * (region & judged)).reshape(len(judged), -1).max(1)
                for k, (loc, spread) in cal.items()}

    vs = scores(vmaps, vj)
    norm = {k: float(np.percentile(s[A], 99)) for k, s in vs.items()}

    def combined(sc: dict[str, np.ndarray], combo: tuple[str, ...]) -> np.ndarray:
        return np.max([sc[k] / norm[k] for k in combo], 0)

    thresholds = {c: float(np.percentile(combined(vs, c)[B], 99)) for c in COMBOS}
    w = model_split(ck, model, warp, "val")
    wl = np.asarray(w.label)
    ws = scores(*maps_of(w.priors.numpy()))
    print(f"{warp}: {len(wl)} parts", flush=True)
    ch = Channels.of(tuple(ck.detector.config.priors))
    shifted = {n: scores(*maps_of(shift(n, vx[B], ch))) for n in SHIFTS}
    rows = {"+".join(c): row_of(combined(vs, c), combined(ws, c), {n: combined(m, c) for n, m in shifted.items()},
                                thresholds[c], vl, vt, B, wl, "+".join(c), 16) for c in COMBOS}
    json.dump({"thresholds": {"+".join(c): t for c, t in thresholds.items()}, "norm": norm, "B": len(B),
               "warp parts": [int((wl == 1).sum()), int((wl == 0).sum())], "rows": rows}, open(out, "w"), indent=1)


if __name__ == "__main__":
    main()
