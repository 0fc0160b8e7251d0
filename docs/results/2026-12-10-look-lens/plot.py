"""The study's figure, as the lens-train study's: defective parts caught against good parts rejected on B, V and N,
the shipped file S against candidate A (and the control R once evaluated), each at its stored threshold.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-10-look-lens/plot.py
"""
import importlib.util
import sys

from read import HERE, lens_train

_spec = importlib.util.spec_from_file_location("lens_train_plot", HERE.parent / "2026-12-08-lens-train/plot.py")
lens_train_plot = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(lens_train_plot)
LABELS = {"S": "S: shipped", "A": "A: look with lens copies", "R": "R: look trained again (control)"}

if __name__ == "__main__":
    models = [m for m in LABELS if (HERE / "eval" / f"{m}-new-1246" / "eval.json").exists()]
    if "A" not in models:
        sys.exit("A is not evaluated yet (make-a.sh)")
    lens_train_plot.plot_sets(lens_train.load, lens_train.SETS, {m: LABELS[m] for m in models},
                              HERE.parent / "2026-12-10-look-lens.png")
