"""``station config``: validate a station.toml and print the settings the station would use."""

from __future__ import annotations

import argparse
import dataclasses

from station.config import load_config


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("config", help="check a station.toml and print the effective settings")
    p.add_argument("--config", default="station.toml", help="configuration file (default: ./station.toml)")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    cfg = load_config(args.config)
    for table in dataclasses.fields(cfg):
        if table.name == "source":
            continue
        print(f"[{table.name}]")
        for key, value in dataclasses.asdict(getattr(cfg, table.name)).items():
            print(f"{key} = {'(not set)' if value is None else repr(value)}")
        print()
    print(f"# {cfg.source}: OK")
    return 0
