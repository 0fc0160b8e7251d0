"""Rule 54's decision (rule54.md), written before its sets were rendered: rule 52's table (decide52.py's
``decide``) for Z against the control K on seed 1157 and its vignetted re-exposure.
Usage: PYTHONPATH=. python decide54.py Z_1157 K_1157 Z_VIGNETTE K_VIGNETTE Z_MODEL"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "2026-11-29-panel-brightness"))
from decide52 import decide

if __name__ == "__main__":
    decide(*sys.argv[1:6], names=("Z", "K"), seed="1157", shift="vignetting 0.2", margin=0.03)
