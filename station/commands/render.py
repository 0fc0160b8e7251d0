"""``station render``: render a polarized training/test set with Mitsuba (format: ``sim.dataset``)."""

from __future__ import annotations

import argparse
import json
import logging
from pathlib import Path

from sim.meshes import EDGE_SHAPES
from station.commands.arguments import number_range, seed

log = logging.getLogger(__name__)


def parse_shard(text: str) -> tuple[int, int]:
    """``K/N`` -> (k, n): this process renders the indices i with i % n == k (k in 0..n-1)."""
    try:
        k, n = (int(x) for x in text.split("/"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"--shard must be K/N (e.g. 0/4), got {text!r}") from None
    if n < 1 or not 0 <= k < n:
        raise argparse.ArgumentTypeError(f"--shard K/N needs 0 <= K < N, got {text!r}")
    return k, n


def azimuths(text: str) -> tuple[float, ...]:
    """``0,180`` -> (0.0, 180.0): ``--dome-segments``."""
    try:
        return tuple(float(x) for x in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"--dome-segments must be degrees separated by commas (e.g. 0,180), "
                                         f"got {text!r}") from None


edge_mm = number_range("--edge-mm", "mm (e.g. 0.3 or 0,0.4)")
"""``0.3`` -> (0.3, 0.3), ``0,0.4`` -> (0.0, 0.4): ``--edge-mm`` (range checks: ``sim.dataset.DatasetSpec``)."""


MAX_COUNT = 10_000_000
"""The most samples one set may hold (its index list is built whole)."""


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("render", help="render a polarized dataset with Mitsuba (resumable, shardable)")
    p.add_argument("--out", required=True, help="dataset folder (created; an existing one is resumed)")
    p.add_argument("--count", type=int, required=True, help="number of samples in the whole set")
    p.add_argument("--defects", type=float, default=0.5, metavar="FRACTION",
                   help="fraction of val/test samples given a defect (default 0.5)")
    p.add_argument("--defects-in-train", action="store_true", help="also put defects into train samples")
    p.add_argument("--heldout", action="store_true",
                   help="every sample in the test split: a held-out evaluation set (give it a seed no training set "
                        "used)")
    p.add_argument("--validation", action="store_true",
                   help="every sample in the val split: a validation set for thresholds and selection (`station "
                        "eval/variation/threshold --val-data`); give it a seed no other set used")
    p.add_argument("--empty-rate", type=float, default=0.0, metavar="FRACTION",
                   help="fraction of samples rendered without the part (same scene, no part in view: for the "
                        "station's presence check; any split; training and evaluation skip them); default 0")
    p.add_argument("--shard", type=parse_shard, default=(0, 1), metavar="K/N",
                   help="render only indices i with i %% N == K (0 <= K < N), for parallel jobs")
    p.add_argument("--seed", type=seed, default=0)
    p.add_argument("--width", type=int, default=640, help="pixels (even); the sensor's native size is 2448x2048")
    p.add_argument("--height", type=int, default=480)
    quality = p.add_mutually_exclusive_group()
    quality.add_argument("--spp", type=int, default=None,
                         help="samples per pixel (default 16; see station bench render)")
    quality.add_argument("--dolp-error", type=float, default=None, metavar="RMSE",
                         help="choose the smallest spp whose DoLP RMSE (curve measured by station bench render, "
                              "sim/spp_table.json) is at most RMSE, e.g. 0.03")
    p.add_argument("--bit-depth", type=int, default=None, choices=(8, 10, 12, 14, 16),
                   help="ADC bits of the raw mosaic; wins over a --config file's [sensor] bit_depth "
                        "(default: that, else 8)")
    p.add_argument("--no-ground-truth", action="store_true",
                   help="raw mosaics only: no AOV pass, no gt.npz (labels still from a shape-index pass)")
    p.add_argument("--mesh", default="", help="PLY/OBJ instead of the built-in USB brick")
    p.add_argument("--materials", default="",
                   help='JSON part -> material map for --mesh, e.g. \'{"*": "pplastic"}\'; for the brick, its '
                        'material keys "plastic" and "metal", e.g. \'{"plastic": {"type": "pplastic", "finish": '
                        '"smooth", "distribution": "ggx"}}\'')
    p.add_argument("--mesh-scale", type=float, default=1.0, help="file units -> metres (0.001 for mm)")
    p.add_argument("--edge-mm", type=edge_mm, default=(0.0, 0.0), metavar="MM[,MM]",
                   help="the brick's body edges chamfered at 45 degrees, that far back along each face (mm; default "
                        "0: sharp, as designed; a moulded part's edges are rounded); LO,HI draws it per part")
    p.add_argument("--edge-shape", choices=EDGE_SHAPES, default="chamfer",
                   help="how --edge-mm breaks the edges: cut at 45 degrees (default), or rounded to that radius "
                        "(shaded smooth; leave chip out of [defects] types: it cuts a crease)")
    p.add_argument("--visibility", action="store_true",
                   help="detectability oracle: render each defective sample's scene again without the defect (two "
                        "pairs at half the spp, around the defect only) and store the defect's SNR per prior in "
                        "params.json (defect.snr, defect.snr_best) and a summary in the manifest")
    p.add_argument("--dome-segments", type=azimuths, default=(), metavar="DEG,DEG[,...]",
                   help="photometric stereo: render each part once per segment of a segmented dome lit in turn, "
                        "at these azimuths of the lit side (degrees from world +x toward +y, e.g. 0,180); needs a "
                        "--config with [scene] ambient_gradient > 0 (how much brighter the lit side is)")
    p.add_argument("--config", action="append", default=[],
                   help="JSON or TOML file with [scene], [defects], [sensor], [variation] overrides; repeat it to "
                        "layer files (a later file's keys win), e.g. a line preset and sim/presets/variation.toml")
    p.add_argument("--variant", default=None, help="Mitsuba variant (default: best available, logged)")
    p.set_defaults(func=run)


def choose_spp(args: argparse.Namespace):
    """``--spp`` (default 16), or the spp the measured error curve gives for ``--dolp-error``: (spp, choice)."""
    from sim.scene import sampler_spp
    from sim.spp import spp_for_dolp_error

    if args.dolp_error is None:
        spp = 16 if args.spp is None else args.spp
        if spp >= 1 and sampler_spp(spp) != spp:
            print(f"station render: --spp {spp} -> {sampler_spp(spp)} (the sampler's x-by-y grid of samples)")
        return spp, None

    choice = spp_for_dolp_error(args.dolp_error, args.width, args.height)
    print(f"station render: {choice.spp} spp for DoLP error <= {args.dolp_error} (predicted "
          f"{choice.predicted_dolp_error:.4f}; curve {choice.table}, {choice.measured})")
    return choice.spp, choice


def build_spec(args: argparse.Namespace, spp: int = 16):
    from sim.dataset import DatasetSpec, read_layers
    from sim.errors import SimError

    extra = read_layers(args.config)
    materials = {}
    if args.materials:
        try:
            materials = json.loads(args.materials)
        except json.JSONDecodeError as exc:
            raise SimError(f"--materials: not JSON ({exc})") from None
        if not isinstance(materials, dict):
            raise SimError("--materials must be a JSON object part -> material")
    sensor = {"bit_depth": 8, **extra.get("sensor", {})}
    if args.bit_depth is not None:  # the command line wins over the layered files (it used to lose silently)
        sensor["bit_depth"] = args.bit_depth
    return DatasetSpec.from_dict({
        "seed": args.seed, "width": args.width, "height": args.height, "spp": spp,
        "ground_truth": not args.no_ground_truth, "defect_fraction": args.defects,
        "defects_in_train": args.defects_in_train, "empty_rate": args.empty_rate, "mesh": args.mesh,
        "visibility": getattr(args, "visibility", False), "heldout": getattr(args, "heldout", False),
        "validation": getattr(args, "validation", False),
        "materials": materials,
        "mesh_scale": args.mesh_scale, "edge_mm": getattr(args, "edge_mm", (0.0, 0.0)),
        "edge_shape": getattr(args, "edge_shape", "chamfer"), "variant": args.variant,
        "scene": extra.get("scene", {}), "defects": extra.get("defects", {}), "sensor": sensor,
        "variation": extra.get("variation", {}), "dome_segments": getattr(args, "dome_segments", ()),
        "view": extra.get("view", {}),
    })


def run(args: argparse.Namespace) -> int:
    from sim.dataset import render_set
    from sim.errors import SimError

    if not 1 <= args.count <= MAX_COUNT:
        raise SimError(f"--count must be in 1..{MAX_COUNT:,}, got {args.count}")
    out = Path(args.out)
    if not args.out.strip():
        raise SimError("--out: empty; name the data set's folder")
    if out.is_dir() and any(out.iterdir()) and not (out / "manifest.json").exists():
        raise SimError(f"--out {out}: holds other files and no manifest.json: not a data set; render into a new "
                       "folder (an existing set is resumed)")
    spp, choice = choose_spp(args)
    render_set(args.out, build_spec(args, spp), args.count, args.shard, choice.to_dict() if choice else None)
    return 0
