"""Summaries of the detectability oracle's values (``params.json``'s ``defect.snr``, see ``sim.oracle``): SNR bins
and per-type tables, shared by the manifest, ``station eval`` and ``station bench visibility``."""

from __future__ import annotations

import json
from collections import defaultdict
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np

from .visibility import CAMERA_PRIORS, POLARIZATION_PRIORS, PRIORS

SNR_BINS = ((0.0, 1.0, "<1"), (1.0, 3.0, "1-3"), (3.0, 5.0, "3-5"), (5.0, 10.0, "5-10"), (10.0, float("inf"), ">10"))
"""(lo, hi, name): a value v falls in the bin with lo <= v < hi."""
VISIBLE_SNR = 5.0
"""Matched-filter SNR above which a defect counts as visible in a prior (the study's threshold)."""
VISIBLE_CNR = 1.0
"""Per-pixel contrast-to-noise (``cnr``) above which a defect stands out pixel by pixel, without knowing its shape."""


def cnr(defect: dict[str, Any], prior: str) -> float:
    """Per-pixel contrast-to-noise of a defect in ``prior``: ``snr / sqrt(pixels)``, the RMS over the defect's
    pixels of difference / noise std. The matched-filter SNR assumes the detector knows the defect's exact shape and
    adds up every pixel; the CNR is what each pixel shows on its own (0 without visible pixels)."""
    px = defect.get("snr_oracle", {}).get("pixels", 0)
    return float(defect["snr"].get(prior, 0.0)) / np.sqrt(px) if px > 0 else 0.0


def snr_bin(value: float) -> str:
    """The name of the ``SNR_BINS`` bin of ``value`` (negative values count as "<1")."""
    return next((name for lo, hi, name in SNR_BINS if lo <= value < hi), SNR_BINS[0][2] if value < 0 else ">10")


def best_snr(defect: dict[str, Any] | None) -> float | None:
    """The best camera prior's SNR of a ``params.json`` defect record; None without oracle values."""
    if not defect or "snr" not in defect:
        return None
    return float(max(defect["snr"].get(p, 0.0) for p in CAMERA_PRIORS))


def summarise(records: Iterable[dict[str, Any]], threshold: float = VISIBLE_SNR) -> list[dict[str, Any]]:
    """Per defect type (and "all"): count, visible count (oracle ran on a visible defect), median SNR per prior over
    the visible ones, and the share of visible defects with SNR > ``threshold`` in intensity, in any polarization
    prior (DoLP or AoLP), in polarization but not intensity, and in any camera prior; the same for the per-pixel
    contrast-to-noise (``cnr``, median per prior; shares with cnr > ``VISIBLE_CNR``). ``records``: ``params.json``
    ``defect`` dicts with oracle values (others are skipped)."""
    groups: dict[str, list[dict]] = defaultdict(list)
    for d in records:
        if d and "snr" in d:
            groups[d.get("type", "?")].append(d)
            groups["all"].append(d)
    rows = []
    for typ in sorted(groups, key=lambda t: (t == "all", t)):
        ds = groups[typ]
        seen = [d for d in ds if d.get("snr_oracle", {}).get("pixels", 1) > 0]
        row: dict[str, Any] = {"type": typ, "n": len(ds), "visible": len(seen)}
        for p in PRIORS:
            vals = [d["snr"].get(p, 0.0) for d in seen]
            row[f"median_{p}"] = float(np.median(vals)) if vals else float("nan")
        for p in CAMERA_PRIORS:
            vals = [d["snr_demosaic"][p] for d in seen if "snr_demosaic" in d]
            row[f"median_demosaic_{p}"] = float(np.median(vals)) if vals else float("nan")
        for p in PRIORS:
            vals = [cnr(d, p) for d in seen]
            row[f"median_cnr_{p}"] = float(np.median(vals)) if vals else float("nan")
        inten = np.array([d["snr"]["intensity"] > threshold for d in seen], bool)
        pol = np.array([max(d["snr"][p] for p in POLARIZATION_PRIORS) > threshold for d in seen], bool)
        row.update({"above_intensity": share(inten), "above_polarization": share(pol),
                    "polarization_only": share(pol & ~inten), "above_any": share(pol | inten)})
        c_int = np.array([cnr(d, "intensity") > VISIBLE_CNR for d in seen], bool)
        c_pol = np.array([max(cnr(d, p) for p in POLARIZATION_PRIORS) > VISIBLE_CNR for d in seen], bool)
        row.update({"cnr_intensity": share(c_int), "cnr_polarization": share(c_pol),
                    "cnr_polarization_only": share(c_pol & ~c_int)})
        rows.append(row)
    return rows


def share(flags: np.ndarray) -> float:
    """Mean of a boolean array; NaN when it is empty."""
    return float(np.mean(flags)) if len(flags) else float("nan")


def read_records(root: str | Path) -> list[dict[str, Any]]:
    """The ``defect`` records with oracle values of every complete sample of a rendered set (params.json only)."""
    out = []
    for p in sorted((Path(root) / "samples").glob("[0-9]" * 6 + "/params.json")):
        d = json.loads(p.read_text()).get("defect")
        if d and "snr" in d:
            out.append(d)
    return out
