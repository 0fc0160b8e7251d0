"""The figure of 2026-12-01-deflectometry.md: defective parts caught on validation seed 1176 by the shipped
recipe alone and joined with each tilt measurement at rule 64's split (all defects, dents, scratches), from the two
readings' tables (this folder's read.md, 2026-12-01-normal-precision/read.md), and the stripes' channels inside the
line's file at its own 1 % (read-2.md).

Usage: python plot.py (from this folder's parent's parent: the repository root)"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

D = "docs/results/2026-12-01-deflectometry"


def rows(path):
    lines = [ln for ln in open(path) if ln.startswith("| ") and not ln.startswith("| seed")]
    out = {}
    for ln in lines:
        cells = [c.strip() for c in ln.strip().strip("|").split("|")]
        name = cells[0].split(" (")[0].replace("RAD alone, the line's 1 %", "RAD alone")
        out[name] = {"good": cells[1].split(" %")[0], "all": float(cells[2].rstrip(" %")),
                     "dent": float(cells[4].rstrip(" %")), "scratch": float(cells[6].rstrip(" %"))}
    return out


r = rows(f"{D}/read.md")
r.update({k: v for k, v in rows("docs/results/2026-12-01-normal-precision/read.md").items() if k == "RAD + IN-1"})
r["RADF"] = next(v for k, v in rows(f"{D}/read-2.md").items() if k.startswith("RADF"))
order = ["RAD alone", "RAD + T", "RAD + IN-1", "RAD + F", "RADF", "RAD + IN-G"]
label = {"RAD alone": "shipped recipe\nalone", "RAD + T": "+ dome halves'\ntilt (T)",
         "RAD + IN-1": "+ normals,\n1 deg error", "RAD + F": "+ stripes'\nphase (F)",
         "RADF": "stripes in the\nline's file (RADF)",
         "RAD + IN-G": "+ exact\nnormals"}
order = [k for k in order if k in r]
x = np.arange(len(order))
fig, ax = plt.subplots(figsize=(9, 3.6))
for j, (key, colour) in enumerate((("all", "0.3"), ("dent", "tab:blue"), ("scratch", "tab:orange"))):
    ax.bar(x + (j - 1) * 0.26, [r[k][key] for k in order], 0.26, color=colour,
           label={"all": "all defects", "dent": "dents", "scratch": "scratches"}[key])
ax.set_xticks(x, [f"{label[k]}\n({r[k]['good']} % good rej.)" for k in order], fontsize=8)
ax.set_ylabel("caught, % (seed 1176, validation)")
ax.set_ylim(0, 100)
ax.legend(fontsize=8, loc="upper left")
ax.set_title("Tilt measurements beside the shipped recipe: the stripes' phase and the others", fontsize=10)
fig.tight_layout()
fig.savefig("docs/results/2026-12-01-deflectometry.png", dpi=110)
