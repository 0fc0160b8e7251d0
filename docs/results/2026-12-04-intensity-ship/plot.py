"""The result page's figure from read.json: S (intensity alone, by make model) against E63 on fresh seeds 1194 and 1195.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-04-intensity-ship/plot.py

Left: defective parts caught per type at each file's stored threshold (held out, 1194, and kinds nobody rendered,
1195), with the good parts each rejected in the legend. Right: image AUROC per type on 1194, and the type's AUROC
when left out of S's look network.
"""
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

HERE = Path(__file__).parent


def main() -> None:
    r = json.loads((HERE / "read.json").read_text())
    h, k = r["held_out_1194"], r["new_kinds_1195"]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.2))
    groups = [("1194 " + t, h, t) for t in h["S"]["by_type"]] + [("1195 " + t, k, t) for t in k["S"]["by_type"]]
    x = np.arange(len(groups))
    for off, m, color in ((-0.2, "S", "tab:blue"), (0.2, "E63", "tab:gray")):
        ax1.bar(x + off, [100 * g[m]["by_type"][t]["caught"] for _, g, t in groups], 0.4, color=color,
                label=f"{m}: {h[m]['good_rejected']} of {h[m]['good']} and {k[m]['good_rejected']} of {k[m]['good']} "
                      "good parts rejected")
    ax1.set_xticks(x, [n.replace("_", " ") for n, _, _ in groups], rotation=35, ha="right")
    ax1.set_ylabel("defective parts caught at the stored threshold (%)")
    ax1.set_title("caught per type: held out (1194), kinds nobody rendered (1195)")
    ax1.legend(fontsize=8, loc="lower left")
    types = list(h["S"]["by_type"])
    x = np.arange(len(types))
    ax2.bar(x - 0.27, [h["S"]["by_type"][t]["auroc"] for t in types], 0.27, color="tab:blue", label="S, trained on")
    ax2.bar(x, [h["E63"]["by_type"][t]["auroc"] for t in types], 0.27, color="tab:gray", label="E63, trained on")
    held = r.get("held_out_types", {})
    ax2.bar(x + 0.27, [held.get(t, {}).get("auroc", np.nan) for t in types], 0.27, color="tab:orange",
            label="S, left out of its look's training")
    ax2.axhline(0.95, color="k", lw=0.7, ls="--")
    ax2.axhline(0.85, color="k", lw=0.7, ls=":")
    ax2.set_xticks(x, [t.replace("_", " ") for t in types])
    ax2.set_ylim(0.5, 1.01)
    ax2.set_ylabel("image AUROC (seed 1194)")
    ax2.set_title("per type; targets 0.95 trained on, 0.85 held out")
    ax2.legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    fig.savefig(HERE.parent / "2026-12-04-intensity-ship.png", dpi=110)


if __name__ == "__main__":
    main()
