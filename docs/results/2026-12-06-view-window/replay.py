"""The view warning replayed on measured lines (docs/results/2026-12-06-view-window.md).

Each part's ``unseen_fraction`` as the shipped file read it on seed 1203 (stop 111's reading: square, and the same
parts with the camera turned 5 degrees; copied here as unseen-1203-*.json) is fed to the rule in the parts' order
and in 2,000 shuffled orders (a line sees its parts in any order): stop 111's (a window of 50, read from 20) and this
stop's (``station.drift.ViewMonitor``: 200, read from 100). Printed per line and rule: whether the parts' own order
warned, the share of shuffled orders that warned at all, and the mean share of parts judged under the warning. Run
from the repository's root."""

import json
from collections import deque

import numpy as np

from station.drift import VIEW_WARN_MIN_PARTS, VIEW_WINDOW, ViewMonitor

HERE = "docs/results/2026-12-06-view-window"


def stop_111(seen: np.ndarray) -> np.ndarray:
    """Per part, whether stop 111's rule had the warning in force after it (over 5 % of the last 50, from 20)."""
    window: deque[bool] = deque(maxlen=50)
    out = []
    for s in seen:
        window.append(bool(s))
        out.append(len(window) >= 20 and sum(window) > 0.05 * len(window))
    return np.array(out)


def stop_112(seen: np.ndarray) -> np.ndarray:
    """Per part, whether ``ViewMonitor`` had the warning in force after it."""
    m = ViewMonitor()
    out = []
    for s in seen:
        m.update(0.01 if s else 0.0)
        out.append(m.warning is not None)
    return np.array(out)


rng = np.random.default_rng(0)
print(f"this stop's rule: window {VIEW_WINDOW}, read from {VIEW_WARN_MIN_PARTS}\n")
print("| line | parts, with some outside the view | rule | its own order warned | shuffled orders that warned "
      "| parts judged under the warning (mean) |\n|---|---|---|---|---|---|")
for name in ("square", "turned5"):
    u = np.array(json.load(open(f"{HERE}/unseen-1203-{name}.json"))["unseen_fraction"]) > 0
    for rule, f in (("stop 111: 50 from 20", stop_111), ("stop 112: 200 from 100", stop_112)):
        runs = [f(rng.permutation(u)) for _ in range(2000)]
        print(f"| seed 1203 {name} | {len(u)}, {int(u.sum())} | {rule} | {'yes' if f(u).any() else 'no'} | "
              f"{100 * np.mean([r.any() for r in runs]):.1f} % | {100 * np.mean([r.mean() for r in runs]):.1f} % |")
