"""``station bench <name>``: benchmarks of run time against error. Each writes JSON + a Markdown table.

A benchmark is a module ``station.benchmarks.<name>`` with ``add_arguments(parser)``, ``run(args) -> int`` and a
one-line module docstring used as its help. The CLI imports every benchmark module to build its parser: keep heavy
imports (torch, mitsuba, gi, polanalyser) inside ``run`` so ``station --help`` stays fast and works everywhere."""

from __future__ import annotations

import argparse
import importlib

BENCHMARKS = ["priors", "render", "camera", "model", "pipeline", "soak", "defects", "faults", "visibility", "shift"]


def first_sentence(doc: str) -> str:
    """The first sentence of a docstring's first paragraph, on one line (a help text never cut mid-sentence)."""
    paragraph = " ".join(doc.strip().split("\n\n")[0].split())
    end = paragraph.find(". ")
    return paragraph if end < 0 else paragraph[:end + 1]


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("bench", help="benchmarks of run time against error (JSON + Markdown table)")
    bench_sub = p.add_subparsers(dest="benchmark", metavar="<benchmark>", required=True)
    for name in BENCHMARKS:
        mod = importlib.import_module(f"station.benchmarks.{name}")
        bp = bench_sub.add_parser(name, help=first_sentence(mod.__doc__ or ""))
        bp.add_argument("--out", default=f"runs/bench/{name}", help="folder for the JSON and Markdown reports")
        mod.add_arguments(bp)
        bp.set_defaults(func=mod.run)
