"""``station view``: the live viewer attached to a station that is already running, through its inspection log.

Reads the log (SQLite, read-only; the station keeps writing) and shows every new part: decision, score,
statistics, and for rejected parts with saved images (``[log] save_rejects``) the intensity, DoLP, AoLP and the
anomaly heatmap. ``station run --viewer`` shows every part's priors instead, from inside the station.
"""

from __future__ import annotations

import argparse

from model.priors import LAYOUTS
from station.commands.arguments import positive_seconds


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("view", help="live viewer attached to a running station (follows its inspection log)",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--db", default="runs/inspection.sqlite", help="the station's inspection log ([log] path)")
    p.add_argument("--layout", default="imx250mzr", choices=tuple(LAYOUTS),
                   help="mosaic layout of the saved raw images ([priors] layout)")
    p.add_argument("--from-start", action="store_true", help="replay the whole log, not only new parts")
    p.add_argument("--seconds", type=positive_seconds, default=None,
                   help="close after this many seconds (default: never)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    import threading
    import time

    from station.log_follower import LogFollower
    from station.viewer import ViewerFeed, run_viewer

    feed = ViewerFeed()
    follower = LogFollower(args.db, feed, layout=args.layout, from_start=args.from_start)
    stop = threading.Event()
    thread = threading.Thread(target=follower.run, args=(stop,), name="log-follower", daemon=True)
    thread.start()
    t_end = time.monotonic() + args.seconds if args.seconds else None
    try:
        run_viewer(feed, done=(lambda: time.monotonic() > t_end) if t_end else None)
    finally:
        stop.set()
        thread.join(timeout=2)
        follower.close()
    return 0
