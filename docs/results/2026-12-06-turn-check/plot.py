"""The turn check's figure: (left) each good part's ``turn_deg`` against the camera's turn, development sets
(turns.json) and the plans' fresh sets (read.json, read-3.json), with the turn warning's +-5 degrees; (right) good
parts rejected against the camera's turn, with the old shift rule (plan 3 of the turns and the sets before it), the
new one before the retries (plan 2's read) and with them.
Run from the repository's root; writes ../2026-12-06-turn-check.png."""
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

D = Path("docs/results/2026-12-06-turn-check")
dev = json.loads((D / "turns.json").read_text())
fresh = json.loads((D / "read.json").read_text()) | json.loads((D / "read-3.json").read_text())
before_retries = json.loads((D / "read-2.json").read_text())["data/turned-20-1229"]
FRESH_TURN = {"data/turned20-1227": 20, "data/turned25-1228": 25, "data/turned-12-1230": -12,
              "data/turned-20-1231": -20}
# good parts rejected, (camera degrees, rejected, good): the old rule from docs/bring-up.md's table (seeds 1211,
# 1217-1219, 1221, 1225, 1226); the new rule on the development sets 20 and 30 (screen.txt) and on the fresh sets
OLD = [(0, 0, 168), (3, 3, 177), (4, 2, 176), (8, 2, 182), (12, 2, 183), (20, 132, 180), (30, 181, 181)]
NEW_DEV = [(20, 2, 180), (30, 91, 181)]  # before the retries (screen.txt)
RETRY_DEV = [(30, 57, 181)]  # with them (screen-2.txt)

fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.8))
rng = np.random.default_rng(0)
for v in dev.values():
    g = np.array([t for t in v["good"] if t is not None and np.isfinite(t)])
    cam = v["camera_deg"]
    a.scatter(cam + rng.uniform(-0.6, 0.6, len(g)), g, s=4, color="tab:blue", alpha=0.4)
for path, cam in FRESH_TURN.items():
    if path in fresh:
        r = fresh[path]
        g = np.array([t for t, lab in zip(r["turn_deg"], r["label"], strict=True) if t is not None and not lab])
        a.scatter(cam + rng.uniform(-0.6, 0.6, len(g)), g, s=4, color="tab:orange", alpha=0.5)
a.axhspan(-5, 5, color="tab:green", alpha=0.1, label="turn warning: median within +-5")
a.plot([-20, 30], [20, -30], color="grey", lw=0.8, ls="--", label="-camera turn")
a.scatter([], [], color="tab:blue", label="development sets (good parts)")
a.scatter([], [], color="tab:orange", label="fresh seeds 1227, 1228, 1230, 1231 (good parts)")
a.set_xlabel("camera turned (degrees)")
a.set_ylabel("turn_deg of each good part (degrees)")
a.legend(fontsize=7, loc="lower left")
a.set_title("each part's turn from the good parts' median")
b.plot([c for c, _, _ in OLD], [100 * r / n for _, r, n in OLD], "o-", color="tab:red", label="old shift rule")
b.plot([c for c, _, _ in NEW_DEV], [100 * r / n for _, r, n in NEW_DEV], "s", color="tab:blue",
       label="new rule without the retries, development sets")
b.plot([c for c, _, _ in RETRY_DEV], [100 * r / n for _, r, n in RETRY_DEV], "D", color="tab:blue", mfc="none",
       label="new rule with the retries, development set")
for path, cam in FRESH_TURN.items():
    if path in fresh:
        r = fresh[path]
        b.plot(cam, 100 * r["good_rejected"] / r["good"], "D", color="tab:orange",
               label="new rule with the retries, fresh seeds" if cam == 20 else None)
b.plot(-20, 100 * before_retries["good_rejected"] / before_retries["good"], "v", color="tab:purple",
       label="new rule without the retries (seed 1229)")
b.axhline(2.1, color="grey", lw=0.8, ls="--", label="2.1 %: the plan's bar")
b.set_xlabel("camera turned (degrees)")
b.set_ylabel("good parts rejected (%)")
b.set_yscale("symlog", linthresh=2)
b.set_ylim(0, 120)
b.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
b.set_title("good parts rejected by the shipped file")
fig.tight_layout()
fig.savefig("docs/results/2026-12-06-turn-check.png", dpi=110)
