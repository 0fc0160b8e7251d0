"""The figure of docs/results/2026-12-06-turns.md from the readings of the view margin study's ``read.py`` (run from
the repository's root): per camera turn, the share of good parts rejected and of defective parts caught at the shipped
threshold, with the view alone and with the frame around it, each with its 95 % Clopper-Pearson interval."""

import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from model.draem.rate_bounds import interval

HERE = Path(__file__).parent
READS = {0: "../2026-12-06-view-margin/read-S.txt", 3: "../2026-12-06-turned3/read.txt",
         4: "read-T4.txt", 5: "../2026-12-06-view-margin/read-T.txt", 8: "read-T8.txt",
         12: "read-T12.txt", 20: "read-T20.txt", 30: "read-T30.txt"}
LINE = re.compile(r"^\S+:test (before|around): (\d+) of (\d+) good rejected .*?; (\d+) of (\d+) defective caught")


def counts() -> dict[tuple[int, str], tuple[int, int, int, int]]:
    """(turn in degrees, arm) -> (good rejected, good parts, defective caught, defective parts)."""
    out = {}
    for turn, name in READS.items():
        for line in (HERE / name).read_text().splitlines():
            if m := LINE.match(line):
                out[turn, m.group(1)] = tuple(int(g) for g in m.groups()[1:])
    return out


def main() -> None:
    got = counts()
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.2))
    for ax, (title, num, den) in zip(axes, (("good parts rejected (%)", 0, 1), ("defective parts caught (%)", 2, 3)),
                                     strict=True):
        for arm, colour, shift, label in (("before", "tab:grey", -0.12, "view alone (border replicated)"),
                                          ("around", "tab:green", 0.12, "frame around (as the station reads)")):
            turns = sorted(t for t, a in got if a == arm)
            k = [got[t, arm][num] for t in turns]
            n = [got[t, arm][den] for t in turns]
            rate = [100 * a / b for a, b in zip(k, n, strict=True)]
            low, high = zip(*(interval(a, b) for a, b in zip(k, n, strict=True)), strict=True)
            err = [[r - 100 * lo for r, lo in zip(rate, low, strict=True)],
                   [100 * hi - r for r, hi in zip(rate, high, strict=True)]]
            ax.errorbar([t + shift for t in turns], rate, yerr=err, fmt="o", color=colour, capsize=3, label=label)
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("camera turned about its optical axis (degrees)", fontsize=8)
        ax.set_xticks(sorted(READS))
        ax.tick_params(labelsize=7)
    axes[0].axhline(2.1, color="tab:red", lw=0.8, ls="--", label="the threshold's promise at 95 % (2.1 %)")
    axes[0].set_ylim(-2, 102)
    axes[0].legend(fontsize=7)
    axes[1].set_ylim(50, 102)
    fig.suptitle("Shipped file at its threshold, fresh seeds 1211 (0, 5), 1217 (3), 1218 (4), 1219 (8), 1221 (12), "
                 "1225 (20), 1226 (30)", fontsize=9)
    fig.tight_layout()
    fig.savefig(HERE.parent / "2026-12-06-turns.png", dpi=110)


if __name__ == "__main__":
    main()
