"""``station defect-pixels``: find a camera's defective pixels in frames of it and write the map the station fills;
from the frames with the lens capped, measure its black level too.

Capture about 20 frames with the lens capped and, for pixels stuck dark as well, 20 of an evenly lit plain target
into the same folder, then::

    station capture --camera aravis --frames 20 --out captures/dark --label good    # lens capped
    station defect-pixels --frames captures/dark --out defect-pixels.png
    # station.toml: [camera] defect_pixels = "defect-pixels.png", and black_level as printed; captures made
    # after that record both, and station import applies them to the set

A pixel is defective where its median over the frames stands at least ``--min-step`` of full scale from its
neighbours of the same polarizer angle, far outside the frame's spread (``model.priors.defect_pixels``). Every PNG
under ``--frames`` is read (a rendered set's or a capture's frames alike); all must be one size, the camera's region
of interest as it streams. Frames whose own fine detail stays put (parts) are refused when too much stands out.

The black level is the median code of the frames whose median is below ``model.priors.black_level.DARK_SHARE`` of
full scale (the lens-capped ones); it is printed, for ``[camera] black_level`` and ``station import --black-level``.
"""

from __future__ import annotations

import argparse


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("defect-pixels", help="find a camera's defective pixels in frames with the lens capped",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--frames", required=True, metavar="DIR", help="folder whose PNGs (any depth) are raw mosaics")
    p.add_argument("--out", required=True, metavar="PNG", help="the map to write (255 on defective pixels)")
    p.add_argument("--bit-depth", type=int, default=None, choices=range(1, 17), metavar="BITS",
                   help="significant bits of the codes (default: the files' own, 8 or 16)")
    p.add_argument("--min-step", type=float, default=None,
                   help="share of full scale a defective pixel stands from its neighbours "
                        "(default: model.priors.defect_pixels.MIN_STEP)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    import cv2

    from model.priors.black_level import DARK_SHARE, measure_black_level
    from model.priors.defect_pixels import MIN_STEP, find_defect_pixels, write_defect_pixel_map
    from station.errors import UserError

    paths = sorted(Path(args.frames).rglob("*.png"))
    if not paths:
        raise UserError(f"--frames {args.frames}: no PNG files")
    raws = []
    for p in paths:
        raw = cv2.imread(str(p), cv2.IMREAD_UNCHANGED)
        if raw is None or raw.ndim != 2:
            raise UserError(f"{p}: not a single-channel PNG (a raw mosaic)")
        raws.append(raw)
    try:
        found = find_defect_pixels(raws, args.bit_depth, min_step=MIN_STEP if args.min_step is None else args.min_step)
        write_defect_pixel_map(args.out, found)
        black = measure_black_level(raws, args.bit_depth)
    except ValueError as exc:
        raise UserError(f"--frames {args.frames}: {exc}") from None
    ys, xs = found.nonzero()
    where = ", ".join(f"({x}, {y})" for y, x in zip(ys[:10], xs[:10], strict=True))
    print(f"{len(ys)} defective pixels in {len(raws)} frames of {found.shape[1]}x{found.shape[0]}"
          f"{': (x, y) ' + where + (' ...' if len(ys) > 10 else '') if len(ys) else ''}; map written to {args.out}")
    if black is None:
        print(f"black level: not measured (no frame's median is below {DARK_SHARE:.0%} of full scale: none was taken "
              "with the lens capped)")
    else:
        print(f"black level: {black[0]} codes, the median of {black[1]} frame(s) with the lens capped; set "
              f"[camera] black_level = {black[0]} and import captures with --black-level {black[0]}")
    return 0
