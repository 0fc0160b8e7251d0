"""The results page's figure: flash caught on seed 1202 by where the fin is, before (B) and with the outline check
(S), from read.txt's numbers. Run from this folder."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

groups = ["front face,\nbottom edge (95)", "front face,\ntop edge (91)", "end faces (52)", "all flash (238)",
          "good parts\nrejected (162)"]
before = [74.7, 13.2, 0.0, 34.9, 0.6]
after = [100.0, 72.5, 0.0, 67.6, 0.6]
fig, ax = plt.subplots(figsize=(8, 3.6))
x = range(len(groups))
ax.bar([i - 0.2 for i in x], before, 0.4, label="shipped file before (B)", color="tab:gray")
ax.bar([i + 0.2 for i in x], after, 0.4, label="with the outline check (S)", color="tab:blue")
for i, (b, a) in enumerate(zip(before, after, strict=True)):
    ax.text(i - 0.2, b + 1.5, f"{b:.0f}", ha="center", fontsize=8)
    ax.text(i + 0.2, a + 1.5, f"{a:.0f}", ha="center", fontsize=8)
ax.set_xticks(list(x), groups, fontsize=8)
ax.set(ylabel="% at the file's threshold", ylim=(0, 110),
       title="Flash on fresh seed 1202 (read once): caught by where the fin is")
ax.legend(fontsize=8, loc="upper right")
fig.tight_layout()
fig.savefig("../2026-12-05-outline.png", dpi=110)
