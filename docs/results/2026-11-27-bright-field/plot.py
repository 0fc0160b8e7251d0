"""Rule 25's figure and the per-face paired gains: image AUROC per defect type and face, D against B, with a paired
bootstrap SE (resampling good and defective parts by index, the same parts under both lines).
Usage: python plot.py runs/df/eval-D data/df-dome-heldout runs/bf/eval-B data/bf-heldout OUT.png [LABEL_D LABEL_B]
(writes faces.json beside this script, or faces-<the second eval folder's name>.json with labels given)."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from faces import auroc, faces_of  # same folder


def main() -> None:
    d_eval, d_data, b_eval, b_data, out = sys.argv[1:6]
    label_d, label_b = sys.argv[6:8] if len(sys.argv) >= 8 else ("D: shipped dome", "B: half dome + bright-field panel")
    sd, gd = faces_of(d_eval, d_data)
    sb, _ = faces_of(b_eval, b_data)
    good = np.array(sorted(set(sd) - set(gd)))
    rng = np.random.default_rng(0)
    rows = []
    for key in sorted(set(gd.values())):
        bad = np.array(sorted(i for i, k in gd.items() if k == key))
        a = [np.array([s[i] for i in idx]) for s in (sd, sb) for idx in (bad, good)]
        base, other = auroc(a[0], a[1]), auroc(a[2], a[3])
        boot = []
        for _ in range(1000):
            bi, gi = rng.choice(bad, len(bad)), rng.choice(good, len(good))
            boot.append(auroc(np.array([sb[i] for i in bi]), np.array([sb[i] for i in gi]))
                        - auroc(np.array([sd[i] for i in bi]), np.array([sd[i] for i in gi])))
        rows.append({"type": key[0], "face": key[1], "n": len(bad), "D": base, "B": other,
                     "gain": other - base, "se": float(np.std(boot))})
    a, b = label_d.split(":")[0], label_b.split(":")[0]  # the lines' letters, as the table's columns
    print(f"| type | face | n | {a} | {b} | {b} - {a} (paired SE) |\n|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['type']} | {r['face']} | {r['n']} | {r['D']:.3f} | {r['B']:.3f} | "
              f"{r['gain']:+.3f} ({r['se']:.3f}) |")
    name = "faces.json" if len(sys.argv) < 8 else f"faces-{Path(b_eval).name}.json"
    (Path(__file__).parent / name).write_text(json.dumps(rows, indent=1))
    fig, ax = plt.subplots(figsize=(8, 3.6))
    x = np.arange(len(rows))
    ax.bar(x - 0.2, [r["D"] for r in rows], 0.4, label=label_d)
    ax.bar(x + 0.2, [r["B"] for r in rows], 0.4, yerr=[r["se"] for r in rows],
           label=label_b)
    ax.set_xticks(x, [f"{r['type'].replace('_', ' ')}\n{r['face']} ({r['n']})" for r in rows], fontsize=7)
    ax.axhline(0.5, color="grey", lw=0.5)
    ax.set(ylim=(0.3, 1.02), ylabel="held-out image AUROC",
           title=f"The same {len(sd)} held-out parts, {a} against {b} (error bar: paired SE of the difference)")
    ax.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main()
