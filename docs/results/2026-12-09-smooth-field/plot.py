"""The study's figure, as the lens-train study's: defective parts caught against good parts rejected on B', V' and
N', the shipped file S against candidate Q (and the control R once evaluated), each at its stored threshold.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-09-smooth-field/plot.py
"""
import importlib.util
import sys

from read import HERE, lens_train

_spec = importlib.util.spec_from_file_location("lens_train_plot", HERE.parent / "2026-12-08-lens-train/plot.py")
lens_train_plot = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(lens_train_plot)
LABELS = {"S": "S: shipped", "Q": "Q: smooth field taken out", "R": "R: the recipe remade (control)"}

if __name__ == "__main__":
    models = [m for m in LABELS if (HERE / "eval" / f"{m}-new-1244" / "eval.json").exists()]
    if "Q" not in models:
        sys.exit("Q is not evaluated yet (run.sh)")
    lens_train_plot.plot_sets(lens_train.load, lens_train.SETS, {m: LABELS[m] for m in models},
                              HERE.parent / "2026-12-09-smooth-field.png")
