"""How visible are the rendered defects in each prior: a property of the data, measured before any model.

For every defective sample of a rendered set (``--splits``, default test) the priors are computed from the raw
mosaic as at the station (bilinear demosaic), cut to the centre square the network sees and compared, on object
pixels, inside the defect mask and in a ring around it (the defect dilated by ``--ring`` of the square's side,
minus the defect). The **visibility** of a defect in a prior is the RMS deviation of its pixels from the ring's
mean over the ring's own RMS deviation from that mean (1 = the defect's pixels stray from the neighbourhood's
typical value as much as the neighbourhood's own pixels do). RMS, not the mean, so that a symmetric change (a
dent tilts normals and AoLP both ways) counts as well as a shift:

- intensity, DoLP: ``rms(inside - mean(ring)) / std(ring)``;
- AoLP: the same with circular differences of 2*phi from the ring's circular mean;
- normal (the rendered ground truth, the learned prior's upper bound): RMS angle of the normals inside to the
  ring's mean direction over the ring's RMS angle to it.

At the full centre square and at the network's input size (``--size``, area-resized). Writes JSON, a Markdown
table (median per defect type and the fraction of defects visible in at least one camera prior, z > ``VISIBLE``)
and a bar plot.
"""

from __future__ import annotations

import argparse
from collections import defaultdict
from pathlib import Path

import numpy as np

from station.commands.arguments import positive_int

PRIORS = ("intensity", "dolp", "aolp", "normal")
VISIBLE = 2.0
"""z above which a defect counts as visible: its pixels stray twice as far as the neighbourhood's own (a piece of
the neighbourhood scores about 1, and the largest of three such scores often exceeds 1)."""
MAPS = ("intensity", "dolp", "aolp_cos", "aolp_sin")


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--data", default="data/brick-v2", help="rendered set with ground truth")
    p.add_argument("--splits", default="test", help="comma-separated splits whose defective samples are measured")
    p.add_argument("--size", type=positive_int, default=128, help="the network's input size (px)")
    p.add_argument("--ring", type=float, default=0.05, help="ring width as a fraction of the square's side")


def _rms_ratio(dev_inside: np.ndarray, dev_ring: np.ndarray) -> float:
    """RMS of the inside's deviations over the ring's (floored at 1e-6)."""
    return float(np.sqrt(np.mean(dev_inside**2)) / max(float(np.sqrt(np.mean(dev_ring**2))), 1e-6))


def scalar_z(inside: np.ndarray, ring: np.ndarray) -> float:
    """rms(inside - mean(ring)) / std(ring) of two 1-D samples."""
    m = ring.mean()
    return _rms_ratio(inside - m, ring - m)


def angle_z(cos_in: np.ndarray, sin_in: np.ndarray, cos_ring: np.ndarray, sin_ring: np.ndarray) -> float:
    """``scalar_z`` for an angle given as (cos, sin) samples (here of 2*AoLP): circular differences (radians,
    wrapped to [-pi, pi]) from the ring's circular mean."""
    m = np.mean(cos_ring + 1j * sin_ring)
    m = m / max(float(abs(m)), 1e-12)
    return _rms_ratio(np.angle((cos_in + 1j * sin_in) * np.conj(m)), np.angle((cos_ring + 1j * sin_ring) * np.conj(m)))


def normal_z(inside: np.ndarray, ring: np.ndarray) -> float:
    """(n, 3) unit normals: RMS angle of ``inside`` to the ring's mean direction over the ring's RMS angle to it."""
    m = ring.mean(0)
    m = m / max(float(np.linalg.norm(m)), 1e-12)
    return _rms_ratio(np.arccos(np.clip(inside @ m, -1.0, 1.0)), np.arccos(np.clip(ring @ m, -1.0, 1.0)))


def visibility(maps: dict[str, np.ndarray], obj: np.ndarray, defect: np.ndarray, ring_px: int) -> dict[str, float]:
    """z per prior for one defect. ``maps``: (h, w) "intensity", "dolp", "aolp_cos", "aolp_sin" and (h, w, 3)
    "normal" (optional); masks (h, w) bool. Empty dict when the visible defect or its ring has too few pixels."""
    import cv2

    d = defect & obj
    k = 2 * ring_px + 1
    ring = cv2.dilate(d.astype(np.uint8), np.ones((k, k), np.uint8)).astype(bool) & ~d & obj
    if d.sum() < 2 or ring.sum() < 5:
        return {}
    out = {"intensity": scalar_z(maps["intensity"][d], maps["intensity"][ring]),
           "dolp": scalar_z(maps["dolp"][d], maps["dolp"][ring]),
           "aolp": angle_z(maps["aolp_cos"][d], maps["aolp_sin"][d], maps["aolp_cos"][ring], maps["aolp_sin"][ring]),
           "pixels": float(d.sum())}
    if "normal" in maps:
        out["normal"] = normal_z(maps["normal"][d], maps["normal"][ring])
    return out


def _resize(maps: dict[str, np.ndarray], obj: np.ndarray, defect: np.ndarray, size: int):
    import cv2

    out = {k: cv2.resize(v.astype(np.float32), (size, size), interpolation=cv2.INTER_AREA) for k, v in maps.items()}
    if "normal" in out:
        out["normal"] /= np.maximum(np.linalg.norm(out["normal"], axis=-1, keepdims=True), 1e-12)
    near = cv2.INTER_NEAREST
    return (out, cv2.resize(obj.astype(np.uint8), (size, size), interpolation=near).astype(bool),
            cv2.resize(defect.astype(np.uint8), (size, size), interpolation=near).astype(bool))


def summarise(per_defect: list[dict]) -> list[dict]:
    """Median z per (scale, defect type), plus "all", and the fraction visible (z > VISIBLE) in each camera prior
    and in at least one (normal excluded: it is ground truth here)."""
    groups: dict[tuple[str, str], list[dict]] = defaultdict(list)
    for r in per_defect:
        groups[(r["scale"], r["type"])].append(r)
        groups[(r["scale"], "all")].append(r)
    rows = []
    for (scale, typ), rs in sorted(groups.items()):
        row = {"scale": scale, "defect": typ, "n": len(rs), "pixels": float(np.median([r["pixels"] for r in rs]))}
        for p in PRIORS:
            vals = [r[p] for r in rs if p in r]
            row[f"{p}_z"] = float(np.median(vals)) if vals else float("nan")
        for p in PRIORS[:3]:
            row[f"visible_{p}"] = float(np.mean([r[p] > VISIBLE for r in rs]))
        row["visible_any"] = float(np.mean([max(r["intensity"], r["dolp"], r["aolp"]) > VISIBLE for r in rs]))
        rows.append(row)
    return rows


def _plot(out: Path, rows: list[dict], scale: str) -> str:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sel = [r for r in rows if r["scale"] == scale]
    fig, ax = plt.subplots(figsize=(7, 3.2))
    x = np.arange(len(sel))
    for k, p in enumerate(PRIORS):
        ax.bar(x + (k - 1.5) * 0.2, [r[f"{p}_z"] for r in sel], 0.2, label=p + (" (ground truth)" if p == "normal"
                                                                                  else ""))
    ax.axhline(1.0, color="k", ls=":", lw=0.8)  # like the neighbourhood
    ax.axhline(VISIBLE, color="k", ls="--", lw=0.8)
    ax.set_xticks(x, [f"{r['defect']}\n(n={r['n']})" for r in sel], fontsize=7)
    ax.set(ylabel="median visibility z", title=f"rendered defects against their surroundings ({scale})")
    ax.legend(fontsize=7)
    name = f"defects-{scale.replace(' ', '')}.png"
    fig.savefig(out / name, dpi=120, bbox_inches="tight")
    plt.close(fig)
    return name


def run(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from model.draem.roi import center_box
    from model.priors import compute_priors
    from sim.dataset import open_dataset
    from station.benchmarks.report import markdown_table, write_report
    from station.errors import UserError

    ds = open_dataset(args.data)
    idx = [i for s in args.splits.split(",") for i in ds.indices(s)]
    per_defect = []
    for i in tqdm(idx, desc="defect visibility", unit="sample"):
        s = ds.load(i)
        if not s.label or s.defect_mask is None or s.object_mask is None:
            continue
        maps = dict(compute_priors(s.raw, ds.manifest.get("layout", "imx250mzr"), priors=list(MAPS),
                                   bit_depth=ds.manifest.get("bit_depth")))
        top, left, h, w = center_box(*s.raw.shape)
        cut = {k: maps[k][top:top + h, left:left + w] for k in MAPS}
        if s.normal is not None:
            cut["normal"] = s.normal[top:top + h, left:left + w]
        obj, dm = s.object_mask[top:top + h, left:left + w], s.defect_mask[top:top + h, left:left + w]
        small = _resize(cut, obj, dm, args.size)
        for scale, (m, o, d), side in ((f"{h} px", (cut, obj, dm), h), (f"{args.size} px", small, args.size)):
            z = visibility(m, o, d, max(1, round(args.ring * side)))
            if z:
                per_defect.append({"index": i, "scale": scale, "type": (s.params.get("defect") or {}).get("type", "?"),
                                   **z})
    if not per_defect:
        raise UserError(f"{args.data}: no defective samples with masks in split(s) {args.splits}")
    rows = summarise(per_defect)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    plots = [_plot(out, rows, scale) for scale in dict.fromkeys(r["scale"] for r in rows)]
    table = (f"Visibility of rendered defects in each prior ({args.data}, {args.splits}; median z: 1 = like the ring "
             f"around the defect; visible_any: z > {VISIBLE:g} in intensity, DoLP or AoLP):\n\n" + markdown_table(
                 rows, ["scale", "defect", "n", "pixels", "intensity_z", "dolp_z", "aolp_z", "normal_z",
                        "visible_intensity", "visible_dolp", "visible_aolp", "visible_any"]))
    write_report(out, "defects", {"args": {k: v for k, v in vars(args).items() if k != "func"}, "rows": rows,
                                  "per_defect": per_defect, "plots": plots}, table)
    print(table)
    print(f"wrote {out / 'defects.json'}, {out / 'defects.md'}, " + ", ".join(str(out / p) for p in plots))
    return 0
