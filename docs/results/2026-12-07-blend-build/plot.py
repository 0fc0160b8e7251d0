"""The figure of ../2026-12-07-blend-build.md: defective parts caught at the 1 % threshold (set on validation, held
fixed), per defect type, the cascade (cascade-reports.json: the file shipped before, its `station eval` reports)
against the blend (the shipped file's reports), on seeds 1194 (rendered kinds) and 1195 (kinds nobody rendered).

Usage: python plot.py [EVAL_1194 EVAL_1195] (the eval.json files; default model/weights/default-eval*/eval.json)."""

import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

HERE = Path(__file__).parent
KEY = "caught_at_1%_false_rejects"


def main(new_1194: str = "model/weights/default-eval/eval.json",
         new_1195: str = "model/weights/default-eval-new-kinds/eval.json") -> None:
    cascade = json.loads((HERE / "cascade-reports.json").read_text())
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), gridspec_kw={"width_ratios": [6, 3]})
    for ax, seed, path in zip(axes, ("1194", "1195"), (new_1194, new_1195), strict=True):
        old = {r["type"]: r for r in cascade[seed]["industrial"]}
        new = {r["type"]: r for r in json.loads(Path(path).read_text())["industrial"]}
        types = list(old)
        x = np.arange(len(types))
        for dx, rows, name in ((-0.2, old, "cascade (shipped before)"), (0.2, new, "blend (shipped)")):
            ax.bar(x + dx, [100 * rows[t][KEY] for t in types], 0.4, label=name)
        ax.set_xticks(x, [f"{t}\n({old[t]['parts']})" for t in types], fontsize=8)
        ax.set_ylim(0, 105)
        ax.set_title(f"seed {seed}" + (": kinds nobody rendered" if seed == "1195" else ": rendered kinds"))
    axes[0].set_ylabel("defective parts caught at the 1 % threshold (%)")
    axes[1].legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(HERE.parent / "2026-12-07-blend-build.png", dpi=110)


if __name__ == "__main__":
    main(*sys.argv[1:])
