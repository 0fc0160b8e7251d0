"""plan.md's read: candidate A (the look network trained with lens copies) against the shipped file S on fresh sets
B (seed 1245 as built), V (B through the whole lens chain) and N (seed 1246, kinds nobody rendered), then the plan's
four bars (read.txt, read.json); then the control R (the look trained again without them) against S the same way
(read-control.txt, read-control.json), which decides nothing.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-10-look-lens/read.py [A] [R]

The tables, matched rates and bars are the lens-train read's (../2026-12-08-lens-train/read.py)."""
import contextlib
import importlib.util
import sys
from pathlib import Path

HERE = Path(__file__).parent
_spec = importlib.util.spec_from_file_location("lens_train_read", HERE.parent / "2026-12-08-lens-train/read.py")
lens_train = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(lens_train)
lens_train.HERE = lens_train._earlier.HERE = HERE  # evaluations in HERE / "eval" / f"{model}-{set}"
lens_train.SETS = {"built-1245": "B: as built (seed 1245)", "allff-1245": "V: B through the lens chain",
                   "new-1246": "N: kinds nobody rendered (seed 1246)"}

if __name__ == "__main__":
    for candidate, name in (("A", "read"), ("R", "read-control")):
        if sys.argv[1:] and candidate not in sys.argv[1:]:
            continue
        lens_train.MODELS = ("S", candidate)
        with open(HERE / f"{name}.txt", "w") as f, contextlib.redirect_stdout(f):
            lens_train.main(f"{name}.json")
