"""Rule 55's decision (rule55.md), written before its sets were scored: rule 52's table (decide52.py's
``decide``) for Z' against X on seed 1158 and its re-exposure through all five imperfections.
Usage: PYTHONPATH=. python decide55.py ZP_1158 X_1158 ZP_ALL X_ALL ZP_MODEL"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "2026-11-29-panel-brightness"))
from decide52 import decide

if __name__ == "__main__":
    decide(*sys.argv[1:6], names=("Z'", "X"), seed="1158", shift="all five imperfections", margin=0.03)
