"""After plan.md's and plan-2.md's reads (not in either plan): S against C at matched rates of good parts rejected
on each set read (the threshold from the set's own good parts, as a line sets its own), from the station eval
reports' scores.csv. ../2026-12-07-matched-rates/curves.py's table.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-07-blend-otherwise/matched.py > .../matched.txt
"""
import sys
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE.parent / "2026-12-07-matched-rates"))
sys.path.insert(0, str(HERE))
from curves import matched  # noqa: E402
from read import SETS, load  # noqa: E402

for name, label in {**SETS, "vignette": "vignetting alone"}.items():
    if not all((HERE / "eval" / f"{m}-{name}" / "scores.csv").exists() for m in ("S", "C")):
        continue
    s, c = load("S", name), load("C", name)
    assert (s["index"] == c["index"]).all()
    print(f"== {label}: {int((s['label'] == 0).sum())} good, {int(s['label'].sum())} defective parts")
    matched(c["score"], s["score"], s["label"] == 1, ("C", "S"))
