"""``station config``: validate a station.toml and print the settings the station would use."""

from __future__ import annotations

import argparse
import dataclasses
import json

from station.config import load_config


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("config", help="check a station.toml and print the effective settings")
    p.add_argument("--config", default="station.toml", help="configuration file (default: ./station.toml)")
    p.set_defaults(func=run)


def toml_value(value: object) -> str:
    """``value`` as a TOML literal (strings with double quotes, true/false, arrays)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)  # a JSON string is a valid TOML basic string
    if isinstance(value, list | tuple):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    return repr(value)


def render_config(cfg: object) -> str:
    """The effective settings as valid TOML: every key, unset ones commented out (``# key = (not set)``)."""
    lines = []
    for table in dataclasses.fields(cfg):  # type: ignore[arg-type]
        if table.name == "source":
            continue
        lines.append(f"[{table.name}]")
        for key, value in dataclasses.asdict(getattr(cfg, table.name)).items():
            lines.append(f"# {key} = (not set)" if value is None else f"{key} = {toml_value(value)}")
        lines.append("")
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    cfg = load_config(args.config)
    print(render_config(cfg))
    print(f"# {cfg.source}: OK")
    return 0
