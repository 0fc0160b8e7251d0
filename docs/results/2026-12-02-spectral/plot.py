"""The shipped file on seed 1184's parts, as rendered and six ways otherwise: good parts rejected at its threshold and
image AUROC (figures from the eval-*/eval.md files beside this script). python plot.py -> checks.png"""
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

HERE = Path(__file__).parent
ROWS = [("as rendered", "asbuilt"), ("spectral variant", "spectral"), ("Mono8 (raw >> 4)", "bit8"),
        ("30 pixels +10 % FS", "warm30"), ("30 pixels stuck at 0", "dead30"), ("30 pixels stuck at FS", "hot30"),
        ("stuck at FS, map filled", "hot30map")]


def figures(name: str) -> tuple[float, int, int]:
    text = (HERE / f"eval-{name}-1184" / "eval.md").read_text()
    auroc = float(text.splitlines()[2].split("|")[5])
    good = re.search(r"observed here [\d.]+ % \((\d+) of (\d+)", text)
    return auroc, int(good.group(1)), int(good.group(2))


vals = [figures(n) for _, n in ROWS]
COLOURS = ["grey"] + ["tab:blue"] * 4 + ["tab:red", "tab:green"]
fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
labels = [label for label, _ in ROWS]
a.barh(labels, [100 * g / n for _, g, n in vals], color=COLOURS)
a.axvline(100 * 4 / 155, ls="--", c="k", lw=0.8)
a.set_xlabel("good parts rejected at the file's threshold (%)\n(dashed: the plan's bar, 4 of 155)")
a.invert_yaxis()
b.barh(labels, [v for v, _, _ in vals], color=COLOURS)
b.set_xlim(0.85, 0.95)
b.set_xlabel("image AUROC")
b.invert_yaxis()
b.set_yticklabels([])
fig.suptitle("The shipped file on seed 1184's 400 parts (155 good), frames made otherwise")
fig.tight_layout()
fig.savefig(HERE / "checks.png", dpi=100)
