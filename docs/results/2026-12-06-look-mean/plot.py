"""The figure of docs/results/2026-12-06-look-mean.md from read.json (run from the repository's root): per fresh set,
defective parts caught at 1 % (the sets' parts rendered as built and kinds nobody rendered) and good parts rejected
(each set), by the shipped cascade C and the candidate D."""

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = Path(__file__).parent
NAMES = {"B": "as built\nseed 1222", "N": "kinds nobody\nrendered, 1223", "G": "GGX lobe\nseed 1224",
         "R": "duller plastic\nseed 1224"}
COLOURS = {"C": "tab:grey", "D": "tab:green"}


def main() -> None:
    read = json.loads((HERE / "read.json").read_text())
    fig, (caught, good) = plt.subplots(1, 2, figsize=(9, 3.6))
    x = range(len(NAMES))
    for k, (d, label) in enumerate([("C", "C, shipped (cascade)"), ("D", "D, blend (not taken)")]):
        off = -0.2 + 0.4 * k
        caught.bar([i + off for i in x], [100 * read[s][d]["caught_1"] for s in NAMES], width=0.4,
                   color=COLOURS[d], label=label)
        good.bar([i + off for i in x], [100 * read[s][d]["good_rejected"] / read[s][d]["good"] for s in NAMES],
                 width=0.4, color=COLOURS[d], label=label)
    for s_i, s in enumerate(NAMES):
        se = 100 * read[s]["D-C_1"]["se"]
        top = 100 * max(read[s]["C"]["caught_1"], read[s]["D"]["caught_1"])
        caught.text(s_i, top + 2, f"D-C {100 * read[s]['D-C_1']['diff']:+.1f}\n(SE {se:.1f})", ha="center",
                    fontsize=7)
    caught.set_ylabel("defective parts caught at 1 % (%)", fontsize=8)
    caught.set_ylim(0, 100)
    good.set_ylabel("good parts rejected at the 1 % threshold (%)", fontsize=8)
    good.axhline(1.0, color="k", lw=0.6, ls=":")
    for ax in (caught, good):
        ax.set_xticks(list(x), list(NAMES.values()), fontsize=7)
        ax.tick_params(labelsize=7)
    caught.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(HERE.parent / "2026-12-06-look-mean.png", dpi=110)


if __name__ == "__main__":
    main()
