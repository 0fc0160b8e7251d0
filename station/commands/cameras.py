"""``station cameras``: list the GenICam cameras this machine can reach.

USB3 Vision cameras are always listed. GigE Vision discovery sends a broadcast on every network interface, so it
runs only with ``--gige-discovery`` (use it on the camera network, not on an office LAN); ``--address IP`` asks
one GigE camera by unicast instead, which sends nothing to anyone else.
"""

from __future__ import annotations

import argparse


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("cameras", help="list GenICam cameras (GigE Vision broadcast only with --gige-discovery)",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--gige-discovery", action="store_true",
                   help="also broadcast GigE Vision discovery on every network interface")
    p.add_argument("--address", action="append", default=[], metavar="IP",
                   help="ask the GigE Vision camera at this IPv4 address (unicast; repeatable)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from drivers.aravis_camera import is_ip_address, list_cameras
    from station.errors import UserError

    for addr in args.address:
        if not is_ip_address(addr):
            raise UserError(f"--address {addr!r}: not an IPv4 address")
    cameras = list_cameras(gige_discovery=args.gige_discovery, addresses=tuple(args.address))
    if not cameras:
        print("no camera found" + ("" if args.gige_discovery else
                                   " (GigE Vision discovery is off: --gige-discovery or --address IP)"))
        return 1
    print(f"{'device id':40} {'vendor':16} {'model':24} {'serial':16} {'address':16} protocol")
    for c in cameras:
        print(f"{c.device_id:40} {c.vendor:16} {c.model:24} {c.serial:16} {c.address:16} {c.protocol}")
    return 0
