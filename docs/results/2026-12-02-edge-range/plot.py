"""Rule 67: the file before (F63) and the shipped file (E63) at their thresholds, on the same parts with sharp,
chamfered and rounded edges: good parts rejected and defective parts caught (decide67.json on seed 1186,
screen.json on seed 1184). python plot.py -> edges.png"""
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

HERE = Path(__file__).parent
rule, screen = (json.loads((HERE / f).read_text()) for f in ("decide67.json", "screen.json"))
SETS = [("1186\nsharp", rule["S"]), ("1186\nchamfer 0.3", rule["E3"]), ("1186\nround 0.3\n(no chips)", rule["R3"]),
        ("1184\nsharp", screen["S"]), ("1184\nchamfer 0.1", screen["E1"]), ("1184\nchamfer 0.3", screen["E3"])]
x = np.arange(len(SETS))
fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.2))
for k, (who, name, colour) in enumerate((("A", "F63, the file before (0.9785)", "tab:grey"),
                                        ("B", "E63, shipped (0.8886)", "tab:blue"))):
    good = [100 * s[who]["good_rejected"] / s[who]["good"] for _, s in SETS]
    caught = [100 * s[who]["caught"] for _, s in SETS]
    a.bar(x + (k - 0.5) * 0.38, good, 0.38, label=name, color=colour)
    b.bar(x + (k - 0.5) * 0.38, caught, 0.38, label=name, color=colour)
a.set_yscale("symlog", linthresh=2)
a.set_yticks([0, 1, 2, 5, 10, 20, 50])
a.set_yticklabels(["0", "1", "2", "5", "10", "20", "50"])
a.set_ylabel("good parts rejected (%)")
b.set_ylim(50, 100)
b.set_ylabel("defective parts caught (%)")
for ax in (a, b):
    ax.set_xticks(x)
    ax.set_xticklabels([n for n, _ in SETS], fontsize=8)
a.legend(fontsize=8)
fig.suptitle("Fitted on parts with a range of edges (E63) or on sharp edges only (F63); each at its own threshold")
fig.tight_layout()
fig.savefig(HERE / "edges.png", dpi=100)
