"""Rule 53's decision (rule53.md), written before its sets were scored: from `station eval` of Y and X on seed 1156
and on its 0.7 px lens re-exposure (each file's own threshold and its 1 % threshold on its own validation set),
paired bootstrap SEs over the parts: rule 52's table (decide52.py's ``decide``) with this rule's names and margin.
Usage: PYTHONPATH=. python decide53.py Y_1156 X_1156 Y_BLUR X_BLUR Y_MODEL"""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "2026-11-29-panel-brightness"))
from decide52 import decide

if __name__ == "__main__":
    decide(*sys.argv[1:6], names=("Y", "X"), seed="1156", shift="0.7 px lens", margin=0.03)
