"""Check 69: the presence rules on side-camera frames (docs/station.md, "The side camera's rule").

For every sample of each set (empty views included), from its raw frame as the station computes its priors: the
DoLP rule's contrast and the row rule's (``station.presence``), and the candidates that did not work: the DoLP
rule's quadratic surface on intensity (``int_contrast``) and the intensity level (``int_mean``, full scale).

Usage (repository root):
    python docs/results/2026-11-30-side-look/presence_probe.py SET [SET ...] > out.json
    python docs/results/2026-11-30-side-look/presence_probe.py --table out.json [out.json ...]
"""

from __future__ import annotations

import json
import sys

import numpy as np

from model.priors.api import compute_priors
from sim.dataset import open_dataset
from station.presence import cell_means, dolp_contrast, row_contrast

THRESHOLD = 0.10


def measures(intensity: np.ndarray, dolp: np.ndarray) -> dict[str, float]:
    return {"dolp_contrast": dolp_contrast(dolp), "row_contrast": row_contrast(intensity),
            "int_contrast": dolp_contrast(intensity),  # the DoLP rule's measure, on the intensity map
            "int_mean": float(cell_means(intensity, 12).mean())}


def probe(roots: list[str]) -> list[dict]:
    out = []
    for root in roots:
        ds = open_dataset(root)
        for k in ds.indices(empty=None):
            s = ds.load(k, ground_truth=False)
            p = compute_priors(s.raws[0], priors=("intensity", "dolp"), bit_depth=ds.manifest.get("bit_depth"))
            out.append({"set": root, "index": k, "empty": bool(s.params.get("empty", False)),
                        "label": int(s.params.get("label", 0)), **measures(p["intensity"], p["dolp"])})
    return out


def table(rows: list[dict]) -> str:
    lines = ["| set | frames | DoLP contrast: min / median / max | called empty at 0.10 | row contrast: min / "
             "median / max | called empty at 0.10 |", "|---|---|---|---|---|---|"]
    for root in dict.fromkeys(r["set"] for r in rows):
        for empty in (False, True):
            rs = [r for r in rows if r["set"] == root and r["empty"] == empty]
            if not rs:
                continue
            cells = []
            for key in ("dolp_contrast", "row_contrast"):
                v = np.array([r[key] for r in rs])
                cells += [f"{v.min():.3f} / {np.median(v):.3f} / {v.max():.3f}", str(int((v < THRESHOLD).sum()))]
            lines.append(f"| {root} | {len(rs)} {'empty views' if empty else 'parts'} | {' | '.join(cells)} |")
    return "\n".join(lines)


if __name__ == "__main__":
    if sys.argv[1] == "--table":
        print(table([r for path in sys.argv[2:] for r in json.load(open(path))]))
    else:
        json.dump(probe(sys.argv[1:]), sys.stdout)
