"""The install footprint (pyproject.toml): the base installs what the priors core needs, each extra adds its
job's packages, and `.[dev]` (what `make setup` installs) is everything."""

from __future__ import annotations

import re
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]

EXTRA_MODULES = ("torch", "tqdm", "scipy", "sklearn", "matplotlib", "mitsuba", "drjit", "trimesh", "serial", "gi",
                 "pyarrow", "pyqtgraph", "PySide6", "polanalyser", "onnx", "onnxscript", "onnxruntime")
"""Import names of every package the extras bring: none may be needed below."""


def _expand(extra: str, seen: frozenset[str] = frozenset()) -> set[str]:
    """The requirements ``.[extra]`` installs on top of the base, through the extras it names."""
    out: set[str] = set()
    for req in PROJECT["optional-dependencies"][extra]:
        m = re.fullmatch(rf"{PROJECT['name']}\[(.+)\]", req)
        if m is None:
            out.add(req)
            continue
        for inner in m.group(1).split(","):
            assert inner not in seen, f"extras loop through {inner}"
            out |= _expand(inner, seen | {extra})
    return out


def test_dev_installs_every_extra_and_all_names_them_all() -> None:
    extras = PROJECT["optional-dependencies"]
    jobs = set(extras) - {"all", "dev"}
    assert extras["all"] == [f"{PROJECT['name']}[{','.join(sorted(jobs, key=list(extras).index))}]"]
    every = set().union(*(set(extras[e]) for e in jobs))
    assert _expand("all") == every
    assert _expand("dev") == every | {"pytest>=8", "hypothesis>=6.100", "ruff>=0.6"}
    assert set(PROJECT["dependencies"]) == {"numpy>=1.26", "opencv-contrib-python-headless>=4.9"}
    # the packages that were all base dependencies before the extras, each still installed by some extra
    before = {"mitsuba", "pyserial", "PyGObject", "torch", "tqdm", "pyarrow", "matplotlib", "trimesh", "scipy",
              "scikit-learn"}
    assert before <= {re.split(r"[<>=!\[]", r)[0] for r in every}


def test_the_priors_core_the_drivers_and_station_help_need_only_the_base() -> None:
    code = f"""
import sys
for name in {EXTRA_MODULES!r}:
    sys.modules[name] = None  # an import of it raises ImportError
import importlib, pkgutil
import numpy as np
import drivers, model.priors
from model.priors import compute_priors
p = compute_priors(np.random.default_rng(0).random((16, 16), dtype=np.float32), priors=("intensity", "dolp", "aolp"))
assert set(p) >= {{"intensity", "dolp", "aolp"}}
for pkg in (model.priors, drivers):
    for m in pkgutil.iter_modules(pkg.__path__):
        if m.name != "torch_ops":  # the priors' torch path
            importlib.import_module(pkg.__name__ + "." + m.name)
import contextlib, io
from station.cli import main  # the entry point the base installs: its help at least
with contextlib.redirect_stdout(io.StringIO()) as help_text, contextlib.suppress(SystemExit):
    main(["--help"])
assert "usage: station" in help_text.getvalue()
print("ok")
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr
