"""The shipped file on seed 1184's parts, as rendered and through a real sensor's response: defective parts caught
and good parts rejected at its threshold (figures from the eval-*/eval.md files; the as-rendered row from
../2026-12-02-spectral). python plot.py -> checks.png"""
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = Path(__file__).parent
ROWS = [("as rendered", HERE.parent / "2026-12-02-spectral" / "eval-asbuilt-1184"),
        ("pedestal 64 codes", HERE / "eval-pedestal64-1184"), ("gain spread 1 %", HERE / "eval-prnu1-1184"),
        ("polarizers 1 deg, ER 100", HERE / "eval-polarizer-1184"), ("all three", HERE / "eval-camera-1184"),
        ("all three, black level stated", HERE / "eval-camera-bl64-1184"),
        ("pedestal 256 codes", HERE / "eval-pedestal256-1184"),
        ("pedestal 256, black level stated", HERE / "eval-pedestal256-bl256-1184")]


def figures(folder: Path) -> tuple[float, int, int]:
    text = (folder / "eval.md").read_text()
    caught = float(re.search(r"\| all \| \d+ \|  \| [\d.]+ \| ([\d.]+) \|", text).group(1))
    good = re.search(r"observed here [\d.]+ % \((\d+) of (\d+)", text)
    return 100 * caught, int(good.group(1)), int(good.group(2))


vals = [figures(f) for _, f in ROWS]
COLOURS = ["grey", "tab:red", "tab:blue", "tab:blue", "tab:red", "tab:green", "tab:red", "tab:green"]
fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4.2))
labels = [label for label, _ in ROWS]
a.barh(labels, [c for c, _, _ in vals], color=COLOURS)
a.set_xlim(60, 80)
a.set_xlabel("defective parts caught at the file's threshold (%, of 245)")
a.invert_yaxis()
b.barh(labels, [100 * g / n for _, g, n in vals], color=COLOURS)
b.axvline(100 * 4 / 155, ls="--", c="k", lw=0.8)
b.set_xlabel("good parts rejected (%, of 155)\n(dashed: the plan's bar, 4 of 155)")
b.invert_yaxis()
b.set_yticklabels([])
fig.suptitle("The shipped file on seed 1184's 400 parts through a real sensor's response")
fig.tight_layout()
fig.savefig(HERE / "checks.png", dpi=100)

# second figure: the part moving during the exposure, and chamfered edges (good parts rejected at the threshold the
# station decides with: the file's own, 0.9785; the adapted model's own for the last bar)
SMEARS = [(0.0, HERE.parent / "2026-12-02-spectral" / "eval-asbuilt-1184")] + [
    (x, HERE / f"eval-motion{x:g}-1184") for x in (0.5, 1, 2, 4, 8)]
moving = [figures(f) for _, f in SMEARS]
EDGES = [("sharp (as rendered)", figures(SMEARS[0][1])), ("chamfer 0.1 mm", figures(HERE / "eval-edge01-1184")),
         ("chamfer 0.3 mm", figures(HERE / "eval-edge03-1184")),
         ("0.3 mm, adapted on 250 good parts", (68.6, 0, 158))]  # read at the adapted threshold (the page)
fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
a.plot([x for x, _ in SMEARS], [100 * g / n for _, g, n in moving], "o-", c="tab:red")
a.axhline(100 * 4 / 155, ls="--", c="k", lw=0.8)
a.set_xscale("symlog", linthresh=0.5)
a.set_xticks([0, 0.5, 1, 2, 4, 8])
a.set_xticklabels(["0", "0.5", "1", "2", "4", "8"])
a.set_xlabel("travel during the exposure (frame px; 0.09 mm each)")
a.set_ylabel("good parts rejected (%, of 155)")
a.set_title("the part moving (dashed: the bar)")
b.barh([e for e, _ in EDGES], [100 * g / n for _, (_, g, n) in EDGES],
       color=["grey", "tab:blue", "tab:red", "tab:green"])
for k, (_, (_, g, n)) in enumerate(EDGES):
    b.text(100 * g / n + 0.5, k, f"{g} of {n}", va="center")
b.axvline(100 * 4 / 155, ls="--", c="k", lw=0.8)
b.set_xlabel("good parts rejected (%)")
b.invert_yaxis()
b.set_title("the part's edges")
fig.suptitle("The shipped file on seed 1184's parts: motion during the exposure, and edges that are not sharp")
fig.tight_layout()
fig.savefig(HERE / "motion-edges.png", dpi=100)
