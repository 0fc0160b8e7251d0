"""Mitsuba rendering: seconds per sample against DoLP/AoLP error for spp in {1, 4, 16, 64}, per variant.

Each scene (``sim.scene.sample_scene`` with seed i, the brick, no defect) is rendered once at ``--ref-spp``
as the reference; then at each spp with ground truth (Stokes pass + 1-spp AOV pass), timed warm (kernels
compiled by a first render). Errors on object pixels of the reference's object mask: DoLP RMSE, mean DoLP bias,
AoLP mean circular error in degrees where the reference DoLP >= 0.05 (AoLP is undefined when unpolarized).
The sensor noise the model sees: DoLP RMSE between priors of a noisy raw (default ``SensorConfig``, 8 bit)
and of the noiseless mosaic of the same reference, on the same pixels. The table states the smallest spp
whose render error is below that.
"""

from __future__ import annotations

import argparse
import time
from typing import Any

import numpy as np

from station.benchmarks.report import markdown_table, write_report

AOLP_MIN_DOLP = 0.05


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--spp", default="1,4,16,64", help="comma-separated samples per pixel")
    p.add_argument("--ref-spp", type=int, default=256, help="reference spp (same scene)")
    p.add_argument("--scenes", type=int, default=2)
    p.add_argument("--width", type=int, default=640)
    p.add_argument("--height", type=int, default=480)
    p.add_argument("--variants", default="best",
                   help="'best', 'all' (adds scalar_spectral_polarized: ~17x slower) or a comma-separated list")


def _errors(ref: tuple, test: tuple, sel: np.ndarray) -> dict[str, float]:
    from model.priors.stokes import aolp, dolp

    d_ref, d = dolp(*ref)[sel], dolp(*test)[sel]
    pol = d_ref >= AOLP_MIN_DOLP
    a_err = np.angle(np.exp(2j * (aolp(*test[1:])[sel][pol] - aolp(*ref[1:])[sel][pol]))) / 2
    return {"dolp_rmse": float(np.sqrt(np.mean((d - d_ref) ** 2))), "dolp_bias": float(np.mean(d - d_ref)),
            "aolp_err_deg": float(np.degrees(np.mean(np.abs(a_err)))) if pol.any() else float("nan"),
            "aolp_px_frac": float(pol.mean())}


def _sensor_dolp_noise(ref: tuple, sel: np.ndarray, seed: int) -> float:
    from model.priors import compute_priors
    from sim.sensor import SensorConfig, ideal_mosaic, simulate

    cfg = SensorConfig()
    frame = simulate(*ref, cfg, np.random.default_rng(seed))
    noisy = compute_priors(frame.raw, priors=("dolp",), bit_depth=cfg.bit_depth)["dolp"]
    clean = compute_priors(ideal_mosaic(frame.s0, frame.s1, frame.s2, cfg), priors=("dolp",))["dolp"]
    return float(np.sqrt(np.mean((noisy[sel] - clean[sel]) ** 2)))


def run(args: argparse.Namespace) -> int:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from sim.meshes import usb_brick
    from sim.render import RenderSettings, render_sample
    from sim.scene import SceneConfig, sample_scene
    from sim.variant import SCALAR_VARIANT, available_variants

    spps = [int(s) for s in args.spp.split(",")]
    avail = available_variants()
    variants = avail[:1] if args.variants == "best" else avail if args.variants == "all" else args.variants.split(",")
    model, cfg = usb_brick(), SceneConfig()
    rows: list[dict[str, Any]] = []
    noise: list[float] = []
    t_start = time.perf_counter()
    for variant in variants:
        per: dict[int, list[dict[str, float]]] = {s: [] for s in spps}
        for i in range(args.scenes):
            params = sample_scene(np.random.default_rng([1234, i]), cfg, model)
            ref_spp = args.ref_spp if variant != SCALAR_VARIANT else min(args.ref_spp, 64)
            ref = render_sample(model, params, None,
                                RenderSettings(args.width, args.height, ref_spp, variant=variant), seed=999)
            sel = ref.object_mask
            ref_s = (ref.s0, ref.s1, ref.s2)
            if variant == variants[0]:
                noise.append(_sensor_dolp_noise(ref_s, sel, i))
            for spp in spps:
                settings = RenderSettings(args.width, args.height, spp, variant=variant)
                if variant != SCALAR_VARIANT:
                    render_sample(model, params, None, settings, seed=1)  # warm: kernels compiled
                t = time.perf_counter()
                out = render_sample(model, params, None, settings, seed=2 + i)
                sec = time.perf_counter() - t
                per[spp].append({"s_per_sample": sec, **_errors(ref_s, (out.s0, out.s1, out.s2), sel)})
                print(f"{variant} scene {i} spp {spp}: {sec:.2f} s, DoLP RMSE {per[spp][-1]['dolp_rmse']:.4f}",
                      flush=True)
        for spp in spps:
            row: dict[str, Any] = {"variant": variant, "spp": spp}
            for key in per[spp][0]:
                row[key] = float(np.nanmean([r[key] for r in per[spp]]))
            rows.append(row)
    sensor_noise = float(np.mean(noise))
    for row in rows:
        row["below_sensor_noise"] = "yes" if row["dolp_rmse"] < sensor_noise else "no"
    enough = {v: next((r["spp"] for r in rows if r["variant"] == v and r["below_sensor_noise"] == "yes"), None)
              for v in variants}
    columns = ["variant", "spp", "s_per_sample", "dolp_rmse", "dolp_bias", "aolp_err_deg", "below_sensor_noise"]
    title = (f"Render {args.width}x{args.height} with ground truth, {args.scenes} scenes, reference "
             f"{args.ref_spp} spp; object pixels. Sensor DoLP noise (8 bit, default SensorConfig): "
             f"{sensor_noise:.4f}. Smallest spp below it: {enough}.\n\n")
    table = title + markdown_table(rows, columns)
    json_path, md_path = write_report(args.out, "render", {
        "benchmark": "render", "width": args.width, "height": args.height, "scenes": args.scenes,
        "ref_spp": args.ref_spp, "sensor_dolp_noise": sensor_noise, "spp_below_sensor_noise": enough,
        "aolp_min_dolp": AOLP_MIN_DOLP, "wall_s": time.perf_counter() - t_start, "rows": rows}, table)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    for v in variants:
        rs = [r for r in rows if r["variant"] == v]
        a1.plot([r["s_per_sample"] for r in rs], [r["dolp_rmse"] for r in rs], "o-", label=v)
        for r in rs:
            a1.annotate(f"{r['spp']} spp", (r["s_per_sample"], r["dolp_rmse"]), fontsize=8)
        a2.plot([r["spp"] for r in rs], [r["aolp_err_deg"] for r in rs], "o-", label=v)
    a1.axhline(sensor_noise, color="gray", ls="--", label="sensor DoLP noise")
    a1.set(xscale="log", yscale="log", xlabel="s per sample", ylabel="DoLP RMSE (object pixels)")
    a2.set(xscale="log", yscale="log", xlabel="spp", ylabel="AoLP mean error (deg)")
    a1.legend(fontsize=8)
    fig.tight_layout()
    png = json_path.with_suffix(".png")
    fig.savefig(png, dpi=100)
    print(table)
    print(f"wrote {json_path}, {md_path} and {png}")
    return 0
