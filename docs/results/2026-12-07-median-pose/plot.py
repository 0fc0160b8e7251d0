"""The median pose's figure, from read.txt and read-2.txt (fresh seeds 1232-1235) and synthetic_turns.txt (the
validation set's good parts turned in the image): (left) good parts rejected by A (the reference from the first part)
and B (from the part nearest the median pose) against the camera's turn, each at its own threshold, with plan 1's
tolerated bar (2.1 %); (middle) defective parts caught; (right) the development screen, good parts rejected against
the parts' turn. Run from the repository's root; writes ../2026-12-07-median-pose.png."""
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

D = Path("docs/results/2026-12-07-median-pose")
CAMERA = {"turned-20-1232": -20, "square-1233": 0, "turned20-1234": 20, "turned20-1235": 20}
LINE = re.compile(r"\(fit on .*?\): (\d+) of (\d+) good rejected; (\d+) of (\d+) defective")

rows = []  # (set, arm, rejected, good, caught, defective)
for name in ("read.txt", "read-2.txt"):
    current = "turned20-1235"
    for line in (D / name).read_text().splitlines():
        if line.startswith("== "):
            current = line.split("/")[-1]
        elif (m := LINE.search(line)) and current in CAMERA:
            arm = "B" if line.startswith("runs/pose-1800/") else "A"
            rows.append((current, arm, *map(int, m.groups())))

screen: dict[str, list[tuple[int, int]]] = {"A": [], "B": []}
arm = "A"
for line in (D / "synthetic_turns.txt").read_text().splitlines():
    if line.startswith("runs/"):
        arm = "B" if line.startswith("runs/pose-1800/") else "A"
    elif m := re.search(r"parts turned\s+([+-]?\d+): (\d+) of", line):
        screen[arm].append((int(m.group(1)), int(m.group(2))))

fig, (a, b, c) = plt.subplots(1, 3, figsize=(14, 4.4))
colour = {"A": "tab:blue", "B": "tab:orange"}
label = {"A": "A: reference from the first part", "B": "B: from the part nearest the median pose"}
for arm_name, shift in (("A", -0.8), ("B", 0.8)):
    pts = [(CAMERA[s] + shift + (1.6 if s == "turned20-1235" else 0), r, g, k, d)
           for s, x, r, g, k, d in rows if x == arm_name]
    a.scatter([p[0] for p in pts], [100 * p[1] / p[2] for p in pts], color=colour[arm_name], label=label[arm_name])
    b.scatter([p[0] for p in pts], [100 * p[3] / p[4] for p in pts], color=colour[arm_name], label=label[arm_name])
    turns = sorted(screen[arm_name])
    c.plot([t for t, _ in turns], [n for _, n in turns], marker="o", color=colour[arm_name], label=label[arm_name])
a.axhline(2.1, color="grey", ls="--", lw=0.8, label="bar: at most 2.1 %")
a.set(xlabel="camera turned (degrees); fresh seeds 1232-1235", ylabel="good parts rejected (%)",
      title="good parts rejected, each at its own threshold")
b.set(xlabel="camera turned (degrees)", ylabel="defective parts caught (%)", title="defective parts caught")
c.set(xlabel="parts turned in the image (degrees from the good parts)", ylabel="good parts rejected (of 370)",
      title="development: validation set turned in the image")
for ax in (a, b, c):
    ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig("docs/results/2026-12-07-median-pose.png", dpi=110)
print(rows)
