"""``station serve-camera``: the virtual polarization camera as a GigE Vision device on loopback.

Aravis's fake GigE Vision camera runs in this process and streams the rendered parts of ``--dataset`` (the
virtual camera's draw: defective with probability ``--defect-rate``) over real GVCP/GVSP, so that
``station run --camera aravis`` with ``[camera] device = "127.0.0.1"`` inspects them over the real protocol.
Ground truth does not travel over GigE Vision: ``--truth FILE`` records one JSON line per frame (device frame id
and timestamp -> sample index, label), joinable to the inspection log's ``camera_timestamp_ns``.

A rehearsal of a camera another tool left non-linear: ``--gamma G`` serves it with GammaEnable on at Gamma G,
``--lut`` with its look-up table on, ``--lock-tone`` with those features read-only (the station then refuses it).

Loopback only (the network rule) unless ``--allow-network``. Stops at Ctrl-C, SIGTERM or after ``--seconds``.
"""

from __future__ import annotations

import argparse
import signal
import threading
import time

from station.commands.arguments import seed


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("serve-camera", help="serve the virtual camera as a GigE Vision device on loopback",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--dataset", required=True, metavar="DIR", help="rendered set to replay (station render --out)")
    p.add_argument("--interface", default="lo", help="interface name or IPv4 address to serve on (default lo)")
    p.add_argument("--allow-network", action="store_true",
                   help="allow a non-loopback interface (the camera then answers on that network)")
    p.add_argument("--defect-rate", type=float, default=0.2, metavar="R",
                   help="fraction of frames showing a defective part (default 0.2)")
    p.add_argument("--empty-rate", type=float, default=0.0, metavar="R",
                   help="fraction of frames showing no part (the set needs empty samples: station render "
                        "--empty-rate; default 0)")
    p.add_argument("--seed", type=seed, default=0, help="draw order of the parts (default 0)")
    p.add_argument("--serial", default="POLARSIM1", help="device serial number (default POLARSIM1)")
    p.add_argument("--truth", default=None, metavar="FILE",
                   help="append each served frame's ground truth to this JSON Lines file")
    p.add_argument("--gamma", type=float, default=None, metavar="G",
                   help="serve with GammaEnable on at Gamma G (0.25-4; default: off, linear)")
    p.add_argument("--lut", action="store_true", help="serve with LUTEnable on (a fixed curve, code^0.5)")
    p.add_argument("--lock-tone", action="store_true", help="make Gamma, GammaEnable and LUTEnable read-only")
    p.add_argument("--seconds", type=float, default=None, metavar="N", help="stop after N seconds (default: never)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from drivers.gv_server import GvCameraServer, ServedTone
    from station.errors import UserError

    if args.seconds is not None and args.seconds <= 0:
        raise UserError(f"--seconds must be > 0, got {args.seconds}")
    server = GvCameraServer(args.dataset, interface=args.interface, defect_rate=args.defect_rate, seed=args.seed,
                            serial=args.serial, truth_path=args.truth, allow_network=args.allow_network,
                            empty_rate=args.empty_rate,
                            tone=ServedTone(gamma=1.0 if args.gamma is None else args.gamma,
                                            gamma_enable=args.gamma is not None, lut_enable=args.lut,
                                            locked=("Gamma", "GammaEnable", "LUTEnable") if args.lock_tone else ()))
    stop = threading.Event()
    previous = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    for s in previous:
        signal.signal(s, lambda *_: stop.set())
    t0 = time.monotonic()
    try:
        with server:
            print(f"serving {args.dataset} as GigE Vision camera {server.serial} at {server.address}: "
                  f"{server.width}x{server.height} {server.pixel_format}"
                  + (f", ground truth to {args.truth}" if args.truth else "") + "\n"
                  f'station.toml: [camera] kind = "aravis", device = "{server.address}", '
                  f'pixel_format = "{server.pixel_format}", width = 0, height = 0', flush=True)
            stop.wait(args.seconds)
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
    print(f"served {server.n_served} frames ({server.n_defective} defective) in {time.monotonic() - t0:.1f} s")
    return 0
