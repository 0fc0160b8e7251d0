"""plan.md's read: the chosen file C (``station pick``'s choice among S, R, R1, R2 on the lens validation set)
against the shipped file S on fresh sets B2 (seed 1247 as built), V2 (B2 through the whole lens chain) and N2 (seed
1248, kinds nobody rendered), then the plan's four bars (read.txt, read.json).

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-11-look-draw/read.py

The tables, matched rates and bars are the lens-train read's (../2026-12-08-lens-train/read.py)."""
import contextlib
import importlib.util
from pathlib import Path

HERE = Path(__file__).parent
_spec = importlib.util.spec_from_file_location("lens_train_read", HERE.parent / "2026-12-08-lens-train/read.py")
lens_train = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(lens_train)
lens_train.HERE = lens_train._earlier.HERE = HERE  # evaluations in HERE / "eval" / f"{model}-{set}"
lens_train.SETS = {"built-1247": "B2: as built (seed 1247)", "allff-1247": "V2: B2 through the lens chain",
                   "new-1248": "N2: kinds nobody rendered (seed 1248)"}
lens_train.MODELS = ("S", "C")

if __name__ == "__main__":
    with open(HERE / "read.txt", "w") as f, contextlib.redirect_stdout(f):
        lens_train.main("read.json")
