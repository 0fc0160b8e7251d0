"""The one command line: ``station <command>``. Each command lives in ``station/commands/<name>.py`` with
``add_parser(subparsers)`` registering its arguments and ``run(args) -> int``; a user-facing failure is raised
as ``UserError`` (or a subclass) and printed as one line, never as a traceback. Keep heavy imports (torch, mitsuba,
gi) inside ``run``: every command module is imported to build the parser."""

from __future__ import annotations

import argparse
import importlib
import logging
import sys
from typing import NoReturn

from station import __version__
from station.errors import USER_ERRORS

COMMANDS = ["run", "view", "config", "export-log", "report", "bench", "render", "cameras", "serve-camera", "train",
            "ensemble", "variation", "residual", "shape", "blend", "threshold", "quantize", "eval", "normals", "import",
            "export", "split", "pick", "capture", "adapt", "compare", "defect-pixels"]
"""Modules under ``station.commands``, in the order ``station --help`` lists them."""
MODULE_OF = {"import": "import_set"}
"""Commands whose module name differs from the command (``import`` is a Python keyword)."""


def _no_default(action: argparse.Action) -> bool:
    """None, an off flag (False itself, not 0) or suppressed: nothing worth showing."""
    return action.default is None or action.default is False or action.default == argparse.SUPPRESS


class DefaultsHelpFormatter(argparse.RawDescriptionHelpFormatter):
    """Every option's help ends with its default, unless it says its default already or has none to say (None,
    a flag that is off); descriptions keep their line breaks."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        if "default" in text.lower() or _no_default(action) or not action.option_strings:
            return text
        return f"{text} (default: %(default)s)"


def _use_formatter(parser: argparse.ArgumentParser) -> None:
    """Defaults shown in every command's help, also for options that have no help text of their own; docstrings
    used as descriptions lose their reStructuredText literal quotes."""
    parser.formatter_class = DefaultsHelpFormatter
    if parser.description:
        parser.description = parser.description.replace("``", "")
    for action in parser._actions:
        if action.help is None and action.option_strings and not _no_default(action):
            action.help = "(default: %(default)s)"
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                _use_formatter(sub)


class OneLineParser(argparse.ArgumentParser):
    """A bad argument is one line naming it (``station <command>: error: ...``), without the usage block: ``-h``
    gives the usage."""

    def error(self, message: str) -> NoReturn:
        self.exit(2, f"{self.prog}: error: {message} (-h for the usage)\n")


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineParser(
        prog="station",
        description="Polar-Ano Station: polarization surface inspection (sim, model, drivers, station).",
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    parser.add_argument("-v", "--verbose", action="store_true", help="debug logging")
    sub = parser.add_subparsers(dest="command", metavar="<command>", required=True)
    for name in COMMANDS:
        importlib.import_module(f"station.commands.{MODULE_OF.get(name, name.replace('-', '_'))}").add_parser(sub)
    _use_formatter(parser)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.DEBUG if args.verbose else logging.INFO,
                        format="%(asctime)s %(levelname)s %(name)s: %(message)s")
    try:
        return int(args.func(args) or 0)
    except USER_ERRORS as exc:
        print(f"station {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:  # a file or folder that cannot be read or written: one line naming it (-v: traceback)
        if args.verbose:
            raise
        where = f"{exc.filename}: " if exc.filename else ""
        print(f"station {args.command}: error: {where}{exc.strerror or exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"station {args.command}: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
