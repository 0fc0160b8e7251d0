"""The two seeds pooled (plan.md's bar 2): good parts rejected and defective parts caught per rule over seeds 1196
and 1197, and the pair's gain over the line camera alone with its standard error (the seeds' paired SEs combined,
each weighted by its defective parts).

    cd docs/results/2026-12-04-two-cameras-intensity && python read.py > read.txt
"""
import json
from math import sqrt
from pathlib import Path

HERE = Path(__file__).parent
reports = [json.loads((HERE / f"two-cameras-{s}.json").read_text()) for s in (1196, 1197)]
n_def = sum(r["rules"][0]["defective"] for r in reports)
for i, rule in enumerate(reports[0]["rules"]):
    good = sum(r["rules"][i]["good"] for r in reports)
    rej = sum(r["rules"][i]["good_rejected"] for r in reports)
    caught = sum(r["rules"][i]["caught"] for r in reports)
    gain = sum(r["rules"][i]["gain_points"] * r["rules"][i]["defective"] for r in reports) / n_def
    se = sqrt(sum((r["rules"][i]["gain_se"] * r["rules"][i]["defective"]) ** 2 for r in reports)) / n_def
    print(f"{rule['rule'].split(' (')[0]:24s} good rejected {rej} of {good} ({100 * rej / good:.1f} %), caught "
          f"{caught} of {n_def} ({100 * caught / n_def:.1f} %), minus the line camera alone {gain:+.1f} (SE {se:.1f})")

# the figure: each rule's share caught per face, the two seeds pooled, and its good parts rejected
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

faces = ("top", "front", "edge", "end")
fig, ax = plt.subplots(figsize=(8, 4))
width = 0.27
for i, rule in enumerate(reports[0]["rules"]):
    good = sum(r["rules"][i]["good"] for r in reports)
    rej = sum(r["rules"][i]["good_rejected"] for r in reports)
    shares = [sum(r["rules"][i]["by_face"][f] for r in reports) / len(reports) for f in faces]
    ax.bar([k + (i - 1) * width for k in range(len(faces))], [100 * s for s in shares], width,
           label=f"{rule['rule']}: {rej} of {good} good rejected")
ax.set_xticks(range(len(faces)), [f"{f} face" for f in faces])
ax.set(ylabel="defective caught (%), seeds' mean", ylim=(0, 135),
       title="the shipped line file beside the side camera, held-out renders")
ax.legend(fontsize=7, loc="upper center", ncol=1)
fig.tight_layout()
fig.savefig(HERE.parent / "2026-12-04-two-cameras-intensity.png", dpi=110)
