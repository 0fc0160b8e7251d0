"""The figure of 2026-12-01-deflectometry.md: defective parts caught on validation seed 1176 by the shipped
recipe alone and joined with each tilt measurement at rule 64's split (all defects, dents, scratches), from the two
readings' tables (this folder's read.md, 2026-12-01-normal-precision/read.md), and the stripes' channels inside the
line's file at its own 1 % (read-2.md). The table reader and the bars are normal-precision's plot.py's.

Usage: python plot.py (from this folder's parent's parent: the repository root)"""
import importlib.util

D = "docs/results/2026-12-01-deflectometry"
spec = importlib.util.spec_from_file_location("precision_plot", "docs/results/2026-12-01-normal-precision/plot.py")
shared = importlib.util.module_from_spec(spec)
spec.loader.exec_module(shared)

r = shared.rows(f"{D}/read.md")
r.update({k: v for k, v in shared.rows("docs/results/2026-12-01-normal-precision/read.md").items()
          if k == "RAD + IN-1"})
r["RADF"] = next(v for k, v in shared.rows(f"{D}/read-2.md").items() if k.startswith("RADF"))
shared.caught_bars(r, ["RAD alone", "RAD + T", "RAD + IN-1", "RAD + F", "RADF", "RAD + IN-G"],
                   {"RAD alone": "shipped recipe\nalone", "RAD + T": "+ dome halves'\ntilt (T)",
                    "RAD + IN-1": "+ normals,\n1 deg error", "RAD + F": "+ stripes'\nphase (F)",
                    "RADF": "stripes in the\nline's file (RADF)", "RAD + IN-G": "+ exact\nnormals"},
                   "Tilt measurements beside the shipped recipe: the stripes' phase and the others",
                   "docs/results/2026-12-01-deflectometry.png", width=9.0)
