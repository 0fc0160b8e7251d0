"""Mitsuba rendering: seconds per sample against DoLP/AoLP error for spp in {1, 2, ..., 64}, per variant.

Each scene (``sim.scene.sample_scene`` with seed i, the brick, no defect) is rendered twice at ``--ref-spp`` with
different seeds (references r1, r2); then at each spp with ground truth (Stokes pass + 1-spp AOV pass), twice:
the first render compiles the kernels, the second is timed; the errors of both are averaged. Errors are on the
object pixels of r1's object mask.

Reference noise: ``test - r1`` is a difference of two independent renders, so its mean square is the test's own
error plus r1's (mean square error adds for independent errors). r1's share is measured as half the mean square
of ``r1 - r2`` and subtracted: ``rmse = sqrt(max(mse(test - r1) - mse(r1 - r2) / 2, 0))``. Done for DoLP, AoLP
(circular difference, pixels with reference DoLP >= 0.05) and the DoLP the model sees; ``dolp_rmse_raw`` is the
uncorrected value. ``dolp_bias`` (mean of test - r1) needs no correction (r1 is practically unbiased).

Two domains: ``dolp_rmse`` per rendered pixel (the error of gt.npz's s0..s2, the curve behind ``station render
--dolp-error``, written by ``--write-table``); ``dolp_rmse_model`` after the sensor's 2x2 mosaic and the priors'
demosaic (``model.priors.compute_priors``), i.e. as the model sees it. The sensor noise the model sees is
measured in that same domain (priors of a noisy 8-bit raw of r1 against priors of its noiseless mosaic), so
``below_sensor_noise`` compares like with like. ``--pipeline-samples`` times whole training samples
(``generate_sample`` + ``write_sample``) per stage; ``--visibility-samples`` times defective samples with and
without the detectability oracle (``station render --visibility``).
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

from station.benchmarks.report import markdown_table, write_report
from station.commands.arguments import even_size, positive_int

AOLP_MIN_DOLP = 0.05


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--spp", default="1,2,4,8,16,30,64",
                   help="comma-separated samples per pixel (rounded up as the sampler does: 32 -> 35)")
    p.add_argument("--ref-spp", type=int, default=256, help="reference spp (same scene, two seeds)")
    p.add_argument("--scenes", type=positive_int, default=2)
    p.add_argument("--width", type=even_size, default=640)
    p.add_argument("--height", type=even_size, default=480)
    p.add_argument("--variants", default="best",
                   help="'best', 'all' (adds scalar_spectral_polarized: ~17x slower) or a comma-separated list")
    p.add_argument("--pipeline-spp", default="16,8", help="spp values at which whole samples are timed ('' = none)")
    p.add_argument("--pipeline-samples", type=int, default=4, help="timed training samples per pipeline spp")
    p.add_argument("--visibility-samples", type=int, default=4,
                   help="defective samples timed with and without station render --visibility (0 = skip)")
    p.add_argument("--visibility-config", default="sim/presets/line.toml",
                   help="preset for the --visibility timing ('' = the default scene randomisation)")
    p.add_argument("--write-table", default="", metavar="JSON",
                   help="also write the measured curve for station render --dolp-error (e.g. sim/spp_table.json)")


def _circular(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """AoLP difference in radians, period pi, in [-pi/2, pi/2)."""
    return np.angle(np.exp(2j * (a - b))) / 2


def _model_dolp(s: tuple) -> np.ndarray:
    """DoLP as the model sees it: noiseless 2x2 mosaic of the default sensor, then the priors' demosaic."""
    from model.priors import compute_priors
    from sim.sensor import SensorConfig, ideal_mosaic

    return compute_priors(ideal_mosaic(*s, SensorConfig()), priors=("dolp",))["dolp"]


def _sensor_dolp_noise(ref: tuple, sel: np.ndarray, seed: int) -> tuple[float, float]:
    """RMS and median absolute DoLP error that the sensor adds, as the model sees it."""
    from model.priors import compute_priors
    from sim.sensor import SensorConfig, simulate

    cfg = SensorConfig()
    frame = simulate(*ref, cfg, np.random.default_rng(seed))
    noisy = compute_priors(frame.raw, priors=("dolp",), bit_depth=cfg.bit_depth)["dolp"]
    err = noisy[sel] - _model_dolp((frame.s0, frame.s1, frame.s2))[sel]
    return float(np.sqrt(np.mean(err**2))), float(np.median(np.abs(err)))


class Reference:
    """Two renders of one scene at the reference spp: r1 is the reference, r1 - r2 measures r1's own noise."""

    def __init__(self, r1, r2) -> None:
        from model.priors.stokes import aolp, dolp

        self.sel = r1.object_mask
        self.s = (r1.s0, r1.s1, r1.s2)
        self.dolp = dolp(*self.s)[self.sel]
        self.pol = self.dolp >= AOLP_MIN_DOLP
        self.aolp = aolp(r1.s1, r1.s2)[self.sel]
        self.model = _model_dolp(self.s)[self.sel]
        d2 = dolp(r2.s0, r2.s1, r2.s2)[self.sel]
        a2 = aolp(r2.s1, r2.s2)[self.sel]
        self.var = {"dolp": float(np.mean((self.dolp - d2) ** 2)) / 2,
                    "aolp": float(np.mean(_circular(a2, self.aolp)[self.pol] ** 2)) / 2 if self.pol.any() else 0.0,
                    "model": float(np.mean((self.model - _model_dolp((r2.s0, r2.s1, r2.s2))[self.sel]) ** 2)) / 2}

    def errors(self, out) -> dict[str, float]:
        """Mean squares against r1 (uncorrected) and the mean DoLP bias / AoLP absolute error."""
        from model.priors.stokes import aolp, dolp

        d = dolp(out.s0, out.s1, out.s2)[self.sel]
        a_err = _circular(aolp(out.s1, out.s2)[self.sel], self.aolp)[self.pol]
        m = _model_dolp((out.s0, out.s1, out.s2))[self.sel]
        return {"mse_dolp": float(np.mean((d - self.dolp) ** 2)), "dolp_bias": float(np.mean(d - self.dolp)),
                "mse_aolp": float(np.mean(a_err**2)) if self.pol.any() else float("nan"),
                "aolp_err_deg": float(np.degrees(np.mean(np.abs(a_err)))) if self.pol.any() else float("nan"),
                "mse_model": float(np.mean((m - self.model) ** 2)),
                "p50_model": float(np.median(np.abs(m - self.model)))}


def _corrected(mse: list[float], var: list[float]) -> float:
    return float(np.sqrt(max(np.nanmean(mse) - np.nanmean(var), 0.0)))


def _pipeline(spp: int, n: int, width: int, height: int) -> dict[str, Any]:
    """Median seconds per whole training sample (generate + write) at ``spp``, per stage. The same samples are
    rendered once before, untimed: each scene structure (background x materials) compiles its kernels once."""
    from sim import dataset as ds

    spec = ds.DatasetSpec(seed=0, width=width, height=height, spp=spp)  # spp as the sampler takes it
    model = ds.prepare(spec)
    train = [i for i in range(1000) if ds.split_of(i) == "train"][:n]
    for i in train:
        ds.generate_sample(spec, model, i)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for i in train:
            c, t0 = time.process_time(), time.perf_counter()
            sample = ds.generate_sample(spec, model, i)
            t1 = time.perf_counter()
            ds.write_sample(tmp, sample)
            t2 = time.perf_counter()
            sec = sample.params["render_seconds"]
            rows.append({"s_per_sample": t2 - t0, "cpu_s": time.process_time() - c, "scene_build_s": sec["build_s"],
                         "stokes_s": sec["stokes_s"], "gt_pass_s": sec.get("gt_s", 0.0),
                         "sensor_etc_s": t1 - t0 - sum(sec.values()), "write_s": t2 - t1,
                         "gt_npz_mb": (Path(tmp) / "samples" / f"{i:06d}" / "gt.npz").stat().st_size / 1e6})
    return {"spp": spp, "samples": len(rows), **{k: float(np.median([r[k] for r in rows])) for k in rows[0]}}


def visibility_cost(spp: int, n: int, width: int, height: int, config: str = "") -> dict[str, Any]:
    """Median seconds per defective sample (``generate_sample``, test split, defect placed and visible) without and
    with the detectability oracle (``DatasetSpec.visibility``), and their ratio. Each sample is rendered once
    before, untimed (kernels compile once per scene structure and oracle window size)."""
    from sim import dataset as ds

    extra = ds.read_overrides(config) if config else {}
    base = {"seed": 0, "width": width, "height": height, "spp": spp, "defect_fraction": 1.0,
            "scene": extra.get("scene", {}), "defects": extra.get("defects", {}), "sensor": extra.get("sensor", {})}
    plain, oracle = ds.DatasetSpec.from_dict(base), ds.DatasetSpec.from_dict({**base, "visibility": True})
    model = ds.prepare(plain)
    rows = []
    for i in (i for i in range(1000) if ds.split_of(i) == "test"):
        if len(rows) >= n:
            break
        if not ds.generate_sample(oracle, model, i).label:
            continue  # the defect is out of view: no oracle renders
        t0 = time.perf_counter()
        ds.generate_sample(plain, model, i)
        t1 = time.perf_counter()
        sample = ds.generate_sample(oracle, model, i)
        t2 = time.perf_counter()
        rows.append({"plain_s": t1 - t0, "visibility_s": t2 - t1,
                     "oracle_s": sample.params["render_seconds"]["oracle_s"]})
    if not rows:
        return {"spp": spp, "samples": 0}
    med = {k: float(np.median([r[k] for r in rows])) for k in rows[0]}
    return {"spp": spp, "preset": config or "default", "samples": len(rows), **med,
            "ratio": float(np.median([r["visibility_s"] / r["plain_s"] for r in rows]))}


def run(args: argparse.Namespace) -> int:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from sim.meshes import usb_brick
    from sim.render import RENDERER_VERSION, RenderSettings, render_sample
    from sim.scene import SceneConfig, sample_scene, sampler_spp
    from sim.variant import SCALAR_VARIANT, available_variants

    spps = sorted({sampler_spp(int(s)) for s in args.spp.split(",")})
    avail = available_variants()
    variants = avail[:1] if args.variants == "best" else avail if args.variants == "all" else args.variants.split(",")
    model, cfg = usb_brick(), SceneConfig()
    rows: list[dict[str, Any]] = []
    noise: list[tuple[float, float]] = []
    ref_noise: list[float] = []
    t_start, load_start = time.perf_counter(), os.getloadavg()[0]
    for variant in variants:
        per: dict[int, list[dict[str, float]]] = {s: [] for s in spps}
        ref_var: list[dict[str, float]] = []
        for i in range(args.scenes):
            params = sample_scene(np.random.default_rng([1234, i]), cfg, model)
            ref_spp = args.ref_spp if variant != SCALAR_VARIANT else min(args.ref_spp, 64)
            ref_settings = RenderSettings(args.width, args.height, ref_spp, variant=variant)
            r1 = render_sample(model, params, None, ref_settings, seed=999)
            r2 = render_sample(model, params, None, RenderSettings(args.width, args.height, ref_spp,
                                                                   ground_truth=False, variant=variant), seed=1000)
            ref = Reference(r1, r2)
            ref_var.append(ref.var)
            if variant == variants[0]:
                noise.append(_sensor_dolp_noise(ref.s, ref.sel, i))
                ref_noise.append(np.sqrt(ref.var["dolp"]))
            for spp in spps:
                settings = RenderSettings(args.width, args.height, spp, variant=variant)
                first = render_sample(model, params, None, settings, seed=1)  # compiles kernels (once per spp)
                t = time.perf_counter()
                out = render_sample(model, params, None, settings, seed=2 + i)
                sec = time.perf_counter() - t
                for o in (first, out):
                    per[spp].append({"s_per_sample": sec, **ref.errors(o)})
                print(f"{variant} scene {i} spp {spp}: {sec:.2f} s, DoLP RMSE (raw) "
                      f"{np.sqrt(per[spp][-1]['mse_dolp']):.4f}", flush=True)
        for spp in spps:
            rs = per[spp]
            v = {k: [r[k] for r in ref_var] for k in ("dolp", "aolp", "model")}
            rows.append({
                "variant": variant, "spp": spp, "s_per_sample": float(np.mean([r["s_per_sample"] for r in rs])),
                "dolp_rmse": _corrected([r["mse_dolp"] for r in rs], v["dolp"]),
                "dolp_rmse_raw": float(np.sqrt(np.mean([r["mse_dolp"] for r in rs]))),
                "dolp_bias": float(np.mean([r["dolp_bias"] for r in rs])),
                "dolp_rmse_model": _corrected([r["mse_model"] for r in rs], v["model"]),
                "dolp_p50_model": float(np.mean([r["p50_model"] for r in rs])),
                "aolp_rmse_deg": float(np.degrees(_corrected([r["mse_aolp"] for r in rs], v["aolp"]))),
                "aolp_err_deg": float(np.nanmean([r["aolp_err_deg"] for r in rs]))})
    sensor_noise, sensor_p50 = (float(x) for x in np.mean(noise, axis=0))
    for row in rows:
        row["below_sensor_noise"] = "yes" if row["dolp_rmse_model"] < sensor_noise else "no"
    enough = {v: next((r["spp"] for r in rows if r["variant"] == v and r["below_sensor_noise"] == "yes"), None)
              for v in variants}
    pipe_spps = sorted({sampler_spp(int(s)) for s in args.pipeline_spp.split(",") if s.strip()} |
                       ({enough[variants[0]]} if enough[variants[0]] and args.pipeline_spp else set()), reverse=True)
    pipeline = [_pipeline(s, args.pipeline_samples, args.width, args.height) for s in pipe_spps
                if args.pipeline_samples > 0]
    vis_cost = [visibility_cost(s, args.visibility_samples, args.width, args.height, args.visibility_config)
                for s in pipe_spps if args.visibility_samples > 0]
    load_end = os.getloadavg()[0]
    columns = ["variant", "spp", "s_per_sample", "dolp_rmse", "dolp_rmse_raw", "dolp_bias", "dolp_rmse_model",
               "dolp_p50_model", "aolp_rmse_deg", "aolp_err_deg", "below_sensor_noise"]
    title = (f"Render {args.width}x{args.height} with ground truth, renderer version {RENDERER_VERSION}, "
             f"{args.scenes} scenes, reference {args.ref_spp} spp (its own DoLP noise "
             f"{np.mean(ref_noise):.4f}, removed in quadrature); object pixels. s_per_sample = Stokes + AOV "
             f"passes (warm). Sensor DoLP noise as the model sees it (8 bit, default SensorConfig): "
             f"RMS {sensor_noise:.4f}, median {sensor_p50:.4f} (dolp_p50_model: median absolute error, reference "
             f"noise included); smallest spp whose dolp_rmse_model is below the RMS: {enough}. Load average "
             f"{load_start:.1f} -> {load_end:.1f} on {os.cpu_count()} cores (shared machine).\n\n")
    table = title + markdown_table(rows, columns)
    if pipeline:
        table += ("\nWhole training samples (generate_sample + write_sample, median of "
                  f"{args.pipeline_samples}, seconds):\n\n")
        table += markdown_table(pipeline, ["spp", "s_per_sample", "cpu_s", "scene_build_s", "stokes_s",
                                           "gt_pass_s", "sensor_etc_s", "write_s", "gt_npz_mb"])
    if vis_cost:
        table += ("\nDefective samples with and without the detectability oracle (station render --visibility: two "
                  "(defective, good) pairs at half the spp, around the defect only; generate_sample, median of "
                  f"{args.visibility_samples}, seconds, preset {args.visibility_config or 'default'}):\n\n")
        table += markdown_table(vis_cost, ["spp", "samples", "plain_s", "visibility_s", "oracle_s", "ratio"])
    json_path, md_path = write_report(args.out, "render", {
        "benchmark": "render", "renderer_version": RENDERER_VERSION, "width": args.width, "height": args.height,
        "scenes": args.scenes, "ref_spp": args.ref_spp, "ref_dolp_noise": float(np.mean(ref_noise)),
        "sensor_dolp_noise": sensor_noise, "sensor_dolp_p50": sensor_p50, "spp_below_sensor_noise": enough,
        "aolp_min_dolp": AOLP_MIN_DOLP,
        "load_average": [load_start, load_end], "wall_s": time.perf_counter() - t_start, "rows": rows,
        "pipeline": pipeline, "visibility_cost": vis_cost}, table)
    if args.write_table:
        _write_table(args, rows, variants[0], sensor_noise, sensor_p50, enough[variants[0]], load_start, load_end)
    _plot(plt, rows, variants, sensor_noise, json_path.with_suffix(".png"))
    print(table)
    print(f"wrote {json_path}, {md_path} and {json_path.with_suffix('.png')}")
    return 0


def _write_table(args: argparse.Namespace, rows: list[dict[str, Any]], variant: str, sensor_noise: float,
                 sensor_p50: float, enough: int | None, load_start: float, load_end: float) -> None:
    import json
    import platform

    from sim.render import RENDERER_VERSION

    points = [{k: r[k] for k in ("spp", "dolp_rmse", "dolp_rmse_model", "dolp_p50_model", "aolp_rmse_deg",
                                 "s_per_sample")}
              for r in rows if r["variant"] == variant]
    table = {"renderer_version": RENDERER_VERSION, "variant": variant, "width": args.width, "height": args.height,
             "measured": (f"station bench render, {args.scenes} brick scenes, reference {args.ref_spp} spp, "
                          f"{time.strftime('%Y-%m-%d')}, {os.cpu_count()} cores {platform.machine()}, load "
                          f"{load_start:.1f}-{load_end:.1f}"),
             "metric": "dolp_rmse: DoLP RMSE per rendered pixel on object pixels, reference noise removed in "
                       "quadrature; dolp_rmse_model: the same after mosaic + demosaic",
             "sensor_dolp_noise": sensor_noise, "sensor_dolp_p50": sensor_p50, "spp_below_sensor_noise": enough,
             "points": points}
    with open(args.write_table, "w") as fh:
        json.dump(table, fh, indent=1)
        fh.write("\n")
    print(f"wrote the spp table {args.write_table}")


def _plot(plt, rows: list[dict[str, Any]], variants: list[str], sensor_noise: float, png) -> None:
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    for v in variants:
        rs = [r for r in rows if r["variant"] == v]
        a1.plot([r["s_per_sample"] for r in rs], [r["dolp_rmse"] for r in rs], "o-", label=f"{v} per pixel")
        a1.plot([r["s_per_sample"] for r in rs], [r["dolp_rmse_model"] for r in rs], "s--",
                label=f"{v} as the model sees it")
        for r in rs:
            a1.annotate(f"{r['spp']} spp", (r["s_per_sample"], r["dolp_rmse"]), fontsize=8)
        a2.plot([r["spp"] for r in rs], [r["aolp_rmse_deg"] for r in rs], "o-", label=v)
    a1.axhline(sensor_noise, color="gray", ls="--", label="sensor DoLP noise (model's view)")
    a1.set(xscale="log", yscale="log", xlabel="s per sample (Stokes + AOV)", ylabel="DoLP RMSE (object pixels)")
    a1.xaxis.set_minor_formatter(plt.NullFormatter())  # log-axis minor labels overlap
    a2.set(xscale="log", yscale="log", xlabel="spp", ylabel="AoLP RMS error (deg)")
    a1.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=100)
