"""How often the station's view warning speaks by chance (docs/results/2026-12-06-view-window.md).

A window of n judged parts warns when over 5 % of them lay partly outside the model's view. A line whose parts do so
independently at rate p warns in a window with the binomial probability of more than 0.05 n of n. Printed for the
rule of stop 111 (a window of 50, read from 20 parts) and this stop's (200, read from 100), at the rates measured
on development sets (docs/results/2026-12-05-outside-view.md): square 0.7 % and 1.7 %, turned 2, 3, 4 and 5 degrees
1.0, 3.0, 8.0 and 10.8 %."""

import math

from scipy.stats import binom

RATES = {"square 0.7 %": 0.007, "square 1.7 %": 0.017, "2 deg 1.0 %": 0.010, "3 deg 3.0 %": 0.030,
         "4 deg 8.0 %": 0.080, "5 deg 10.8 %": 0.108}
print("| parts in the window | warns at | " + " | ".join(RATES) + " |\n|---|---|" + "---|" * len(RATES))
for n in (20, 30, 39, 50, 100, 150, 200):
    k = math.floor(0.05 * n) + 1
    print(f"| {n} | {k} or more | " + " | ".join(f"{100 * binom.sf(k - 1, n, p):.2f} %" for p in RATES.values()) + " |")

# the plot: chance of a warning against the parts in the window, both rules' thresholds
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ns = np.arange(20, 301)
fig, ax = plt.subplots(figsize=(6.4, 3.6))
for name, p in RATES.items():
    ax.plot(ns, [binom.sf(math.floor(0.05 * n), n, p) for n in ns], label=name)
for n, text in ((50, "stop 111: 50"), (200, "stop 112: 200")):
    ax.axvline(n, color="grey", ls=":", lw=1)
    ax.text(n + 3, 3e-4, text, fontsize=7, rotation=90, va="center")
ax.set(xlabel="parts in the window", ylabel="chance the window warns (over 5 %)", yscale="log", ylim=(1e-5, 1.5),
       title="the view warning: a square line's chance clusters against a turned line")
ax.legend(fontsize=7, loc="lower right")
fig.savefig("docs/results/2026-12-06-view-window.png", dpi=110, bbox_inches="tight")
