"""The study's figure, as the lens-train study's: defective parts caught against good parts rejected on B2, V2 and N2,
the shipped file S against C (the draw station pick kept), each at its stored threshold.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-11-look-draw/plot.py
"""
import importlib.util

from read import HERE, lens_train

_spec = importlib.util.spec_from_file_location("lens_train_plot", HERE.parent / "2026-12-08-lens-train/plot.py")
lens_train_plot = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(lens_train_plot)

if __name__ == "__main__":
    lens_train_plot.plot_sets(lens_train.load, lens_train.SETS, {"S": "S: shipped", "C": "C: the draw kept (R2)"},
                              HERE.parent / "2026-12-11-look-draw.png")
