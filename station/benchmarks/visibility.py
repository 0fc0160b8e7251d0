"""Defect detectability under candidate line presets: the oracle's SNR per prior for the same defects (same seeds).

For each ``--config`` preset (a ``station render --config`` file: [scene], [defects], [sensor]), samples are drawn
with a defect in every one (``defect_fraction`` 1, any split) from the same ``--seed``, and the first ``--per-type``
indices of each defect type are measured: the same indices draw the same defect types and sizes under every preset
(where on the part they land depends on the camera: defects are placed on faces that face it). Each defect is
measured by the detectability oracle (``sim.oracle.defect_snr``: paired renders with and without it, around the
defect only, matched-filter SNR against the preset's sensor noise). Per preset and defect type the report gives
the median SNR per prior and the share of visible defects with SNR > ``--threshold`` in intensity alone versus in a
polarization prior (DoLP or AoLP). Resumable: per-defect records are appended to ``<out>/<preset>.jsonl`` and
skipped on the next run. Writes ``visibility.json``, ``visibility.md`` and ``visibility.png``.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path
from typing import Any

import numpy as np

from station.commands.arguments import even_size, positive_int

COLUMNS = ["preset", "type", "n", "visible", "median_intensity", "median_dolp", "median_aolp", "median_normal",
           "above_intensity", "above_polarization", "polarization_only", "above_any"]

CNR_COLUMNS = ["preset", "type", "median_cnr_intensity", "median_cnr_dolp", "median_cnr_aolp", "median_cnr_normal",
               "cnr_intensity", "cnr_polarization", "cnr_polarization_only"]


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--config", action="append", required=True, metavar="TOML",
                   help="a candidate preset (repeat for each; e.g. sim/presets/line.toml)")
    p.add_argument("--per-type", type=int, default=30, help="defects measured per type and preset")
    p.add_argument("--count", type=int, default=400,
                   help="sample indices scanned for --per-type defects of each type (the first ones of each type)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--width", type=even_size, default=640)
    p.add_argument("--height", type=even_size, default=480)
    p.add_argument("--spp", type=positive_int, default=8, help="spp of each of the oracle's four renders per defect")
    p.add_argument("--threshold", type=float, default=5.0, help="SNR above which a defect counts as visible")


def preset_name(path: str) -> str:
    return Path(path).stem


def preset_spec(path: str, args: argparse.Namespace):
    """The ``DatasetSpec`` a preset renders under in this benchmark: every sample defective, oracle on."""
    from sim.dataset import DatasetSpec, read_overrides

    extra = read_overrides(path)
    return DatasetSpec.from_dict({"seed": args.seed, "width": args.width, "height": args.height, "spp": args.spp,
                                  "defect_fraction": 1.0, "defects_in_train": True, "visibility": True,
                                  "scene": extra.get("scene", {}), "defects": extra.get("defects", {}),
                                  "sensor": extra.get("sensor", {})})


def select_indices(spec, model, per_type: int, count: int) -> list[int]:
    """The first ``per_type`` indices below ``count`` that draw each defect type (the type of an index is the same
    under every preset: it comes from the same random stream, before anything the preset changes is used)."""
    from sim.dataset import draw_sample

    seen: dict[str, int] = {}
    out = []
    for i in range(count):
        kind = draw_sample(spec, model, i).defect.info["type"]
        if seen.get(kind, 0) < per_type:
            seen[kind] = seen.get(kind, 0) + 1
            out.append(i)
    return out


def measure_preset(path: str, args: argparse.Namespace, out: Path, progress: bool = True) -> list[dict[str, Any]]:
    """Per-defect records of one preset (``params.json``-style defect dicts with the oracle's keys plus ``index``),
    resuming from ``<out>/<preset>.jsonl``."""
    from tqdm import tqdm

    from sim.dataset import draw_sample, oracle_record, prepare
    from sim.oracle import defect_snr
    from sim.render import RenderSettings

    spec = preset_spec(path, args)
    model = prepare(spec)
    log = out / f"{preset_name(path)}.jsonl"
    done = {}
    if log.exists():
        for line in log.read_text().splitlines():
            if line.strip():
                r = json.loads(line)
                done[r["index"]] = r
    settings = RenderSettings(spec.width, spec.height, spec.spp, False, spec.max_depth,
                              spec.scene.background_size_m, spec.variant)
    wanted = select_indices(spec, model, args.per_type, args.count)
    with open(log, "a") as fh:
        for i in tqdm([i for i in wanted if i not in done], desc=preset_name(path), unit="defect",
                      disable=not progress):
            draw = draw_sample(spec, model, i)
            if draw.defect is None:
                continue
            result, _ = defect_snr(draw.part, draw.params, draw.defect, settings, draw.mitsuba_seed, spec.sensor)
            rec = {"index": i, **draw.defect.info, **oracle_record(result)}
            fh.write(json.dumps(rec) + "\n")
            fh.flush()
            done[i] = rec
    return [done[i] for i in wanted if i in done]


def _plot(out: Path, rows: list[dict[str, Any]], presets: list[str], threshold: float, cnr: float) -> str:
    """Shares per preset and defect type: SNR > threshold (top) and per-pixel CNR > cnr (bottom), in intensity
    (left) and in DoLP or AoLP (right)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    types = list(dict.fromkeys(r["type"] for r in rows))
    panels = ((f"SNR > {threshold:g} in intensity", "above_intensity"), (f"SNR > {threshold:g} in DoLP or AoLP",
                                                                        "above_polarization"),
              (f"per-pixel CNR > {cnr:g} in intensity", "cnr_intensity"),
              (f"per-pixel CNR > {cnr:g} in DoLP or AoLP", "cnr_polarization"))
    fig, axes = plt.subplots(2, 2, figsize=(12, 2 * (1.5 + 0.42 * len(presets))))
    y = np.arange(len(presets))
    hgt = 0.8 / len(types)
    for ax, (title, key) in zip(axes.ravel(), panels, strict=True):
        for k, t in enumerate(types):
            sel = {r["preset"]: r for r in rows if r["type"] == t}
            ax.barh(y + (k - (len(types) - 1) / 2) * hgt, [sel[p][key] if p in sel else 0 for p in presets], hgt,
                    label=t)
        ax.set_yticks(y, presets, fontsize=7)
        ax.set(xlim=(0, 1), title=f"share of defects with {title}")
        ax.invert_yaxis()
    axes[0, 1].legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(out / "visibility.png", dpi=72)
    plt.close(fig)
    return "visibility.png"


def run(args: argparse.Namespace) -> int:
    from sim.detectability import VISIBLE_CNR, summarise
    from station.benchmarks.report import markdown_table, write_report
    from station.errors import UserError

    if args.count < 1:
        raise UserError(f"--count must be >= 1, got {args.count}")
    names = [preset_name(c) for c in args.config]
    if len(set(names)) != len(names):
        raise UserError(f"--config: presets need distinct file names (they name the rows): {names}")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    rows, per_defect, cost = [], {}, {}
    for path in args.config:
        name = preset_name(path)
        recs = measure_preset(path, args, out)
        per_defect[name] = recs
        secs = [r["snr_oracle"]["seconds"] for r in recs if r["snr_oracle"]["pixels"] > 0]
        cost[name] = float(np.median(secs)) if secs else float("nan")
        rows += [{"preset": name, **r} for r in summarise(recs, args.threshold)]
    table = (f"Defect detectability per preset (matched-filter SNR against sensor noise, sim/oracle.py; "
             f"{args.per_type} defects per type and preset, seed {args.seed}, {args.width}x{args.height}, "
             f"{args.spp} spp per oracle render; "
             f"medians over visible defects; above_*: share with SNR > {args.threshold:g}):\n\n"
             + markdown_table(rows, COLUMNS))
    table += (f"\n\nPer-pixel contrast-to-noise (cnr = snr / sqrt(pixels)), median, and the share with cnr > "
              f"{VISIBLE_CNR:g} in intensity versus in DoLP or AoLP:\n\n") + markdown_table(rows, CNR_COLUMNS)
    table += "\n\nDemosaic (priors through the 2x2 mosaic and bilinear demosaic), median SNR:\n\n" + markdown_table(
        rows, ["preset", "type", "median_demosaic_intensity", "median_demosaic_dolp", "median_demosaic_aolp"])
    plots = [_plot(out, rows, names, args.threshold, VISIBLE_CNR)]
    write_report(out, "visibility", {"args": {k: v for k, v in vars(args).items() if k != "func"},
                                     "rows": rows, "oracle_seconds_median": cost, "per_defect": per_defect,
                                     "wall_s": time.perf_counter() - t0, "plots": plots}, table)
    print(table)
    print(f"wrote {out / 'visibility.json'}, {out / 'visibility.md'}, {out / plots[0]}")
    return 0
