"""The page's figure: defective parts caught at the 1 % threshold and image AUROC per defect type, seed 1182, for
RAD (the shipped recipe's priors), + the learned normal prior (RADN) and + the renderer's normals (RADN-G, a bound).

Usage: python plot.py RUNS_DIR OUT.png (RUNS_DIR: run.sh's runs/c77)"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

runs, out = sys.argv[1:3]
files = {"RAD": "eval-1182-V1", "RADN (learned normal)": "eval-1182-RADN", "RADN-G (renderer's normals)":
         "eval-1182-RADNG"}
types = ["all", "chip", "dent", "missing_stud", "scratch", "stain"]
fig, ax = plt.subplots(1, 2, figsize=(11, 3.6))
for k, (name, folder) in enumerate(files.items()):
    rows = {r["type"]: r for r in json.load(open(f"{runs}/{folder}/eval.json"))["industrial"]}
    x = np.arange(len(types)) + (k - 1) * 0.27
    ax[0].bar(x, [100 * rows[t]["caught_at_1%_false_rejects"] for t in types], 0.27, label=name)
    ax[1].bar(x, [rows[t]["image_auroc"] for t in types], 0.27, label=name)
for a, title in zip(ax, ("caught at the 1 % threshold (%)", "image AUROC"), strict=True):
    a.set_xticks(np.arange(len(types)), [t.replace("_", " ") for t in types])
    a.set_title(f"seed 1182 (400 parts): {title}", fontsize=9)
ax[1].set_ylim(0.5, 1.0)
ax[0].legend(fontsize=7, loc="lower left")
fig.tight_layout()
fig.savefig(out, dpi=80)
