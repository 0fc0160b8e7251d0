"""The figure of 2026-12-01-normal-precision.md: defective parts caught on validation seed 1176 by the shipped
recipe alone and joined with each tilt measurement at rule 64's split (all defects, dents, scratches), from the two
readings' tables (this folder's read.md, 2026-12-01-tilt-apart/read.md). `rows` and `caught_bars` also make
2026-12-01-deflectometry's figure (its plot.py).

Usage: python plot.py (from this folder's parent's parent: the repository root)"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

D = "docs/results/2026-12-01-normal-precision"


def rows(path):
    """A join reading's table (tilt-apart/read.py's layout) -> {row name: good parts rejected, caught: all, dents,
    scratches}; "RAD alone, the line's 1 %" is named "RAD alone"."""
    lines = [ln for ln in open(path) if ln.startswith("| ") and not ln.startswith("| seed")]
    out = {}
    for ln in lines:
        cells = [c.strip() for c in ln.strip().strip("|").split("|")]
        name = cells[0].split(" (")[0].replace("RAD alone, the line's 1 %", "RAD alone")
        out[name] = {"good": cells[1].split(" %")[0], "all": float(cells[2].rstrip(" %")),
                     "dent": float(cells[4].rstrip(" %")), "scratch": float(cells[6].rstrip(" %"))}
    return out


def caught_bars(r, order, label, title, out, width=8.0):
    """Bars of all defects, dents and scratches caught for the rows ``order`` of ``r`` present, saved to ``out``."""
    order = [k for k in order if k in r]
    x = np.arange(len(order))
    fig, ax = plt.subplots(figsize=(width, 3.6))
    for j, (key, colour) in enumerate((("all", "0.3"), ("dent", "tab:blue"), ("scratch", "tab:orange"))):
        ax.bar(x + (j - 1) * 0.26, [r[k][key] for k in order], 0.26, color=colour,
               label={"all": "all defects", "dent": "dents", "scratch": "scratches"}[key])
    ax.set_xticks(x, [f"{label[k]}\n({r[k]['good']} % good rej.)" for k in order], fontsize=8)
    ax.set_ylabel("caught, % (seed 1176, validation)")
    ax.set_ylim(0, 100)
    ax.legend(fontsize=8, loc="upper left")
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    r = rows(f"{D}/read.md")
    r.update({k: v for k, v in rows("docs/results/2026-12-01-tilt-apart/read.md").items() if k == "RAD + T"})
    caught_bars(r, ["RAD alone", "RAD + T", "RAD + IN-3", "RAD + IN-1", "RAD + IN-G"],
                {"RAD alone": "shipped recipe\nalone", "RAD + T": "+ dome halves'\ntilt (T)",
                 "RAD + IN-3": "+ normals,\n3 deg error", "RAD + IN-1": "+ normals,\n1 deg error",
                 "RAD + IN-G": "+ exact\nnormals"},
                "A tilt measurement joined at rule 64's split: how fine it must be",
                "docs/results/2026-12-01-normal-precision.png")
