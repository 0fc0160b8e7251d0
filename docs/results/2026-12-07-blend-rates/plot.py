"""Plan 2's figure, from read.txt: for each fresh set, defective parts caught by the shipped file's cascade C and its
blend D when at most 1 %, 2 % and 5 % of the set's good parts are rejected (D's bar: the bootstrap SE of D - C). Run
from the repository's root with PYTHONPATH=.; writes ../2026-12-07-blend-rates.png."""
import sys
from pathlib import Path

sys.path.insert(0, "docs/results/2026-12-07-matched-rates")
from plot import plot  # matched-rates's plot.py (inserted first)

plot(Path("docs/results/2026-12-07-blend-rates/read.txt"),
     {"square-1238": "square camera, fresh seed 1238\n(360 good, 240 defective)",
      "rough-1239": "a duller plastic, fresh seed 1239\n(240 good, 160 defective)"},
     ("C: the cascade (the station's decision)", "D: the blend (bar: SE of D - C)"),
     "docs/results/2026-12-07-blend-rates.png")
