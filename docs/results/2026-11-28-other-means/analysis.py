"""Rule 35's reading: the shipped model at its own threshold on the same parts rendered three ways (S as shipped, G
with GGX microfacets, E with IOR 1.54), with paired bootstrap SEs of the differences, the good parts' noise level and
highlight share, and a figure (good parts' scores; one good part's intensity and map under each).
Usage (repository root): python analysis.py MODEL OUT_PREFIX NAME=EVAL_DIR:DATA ... (the first is the reference);
prints markdown, writes OUT_PREFIX.json and OUT_PREFIX.png."""

from __future__ import annotations

import csv
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.datasets import load_split

RESAMPLES = 1000


def scores(eval_dir: str) -> dict[int, tuple[int, str, float]]:
    """index -> (label, defect type, decision score) from a station eval report's scores.csv."""
    rows = csv.DictReader(open(f"{eval_dir}/scores.csv"))
    return {int(r["index"]): (int(r["label"]), r["defect_type"], float(r["score"])) for r in rows}


def rates(labels: np.ndarray, flagged: np.ndarray) -> tuple[float, float]:
    """(good parts rejected, defective parts caught) as shares."""
    return float(flagged[labels == 0].mean()), float(flagged[labels == 1].mean())


def paired_se(labels: np.ndarray, a: np.ndarray, b: np.ndarray, rng: np.random.Generator) -> tuple[float, float]:
    """Bootstrap SEs of b - a in (good rejected, defective caught), resampling parts (the same parts in both)."""
    good, bad = np.flatnonzero(labels == 0), np.flatnonzero(labels == 1)
    d = []
    for _ in range(RESAMPLES):
        g, k = rng.choice(good, len(good)), rng.choice(bad, len(bad))
        d.append((b[g].mean() - a[g].mean(), b[k].mean() - a[k].mean()))
    return tuple(np.std(np.array(d), axis=0))


def main() -> None:
    model, out = sys.argv[1:3]
    sets = [arg.split("=", 1) for arg in sys.argv[3:]]
    ck = load_checkpoint(model)
    thr, cfg, v = ck.threshold, ck.detector.config, ck.detector.variation
    per = {name: scores(spec.split(":")[0]) for name, spec in sets}
    ref = sets[0][0]
    index = sorted(per[ref])
    assert all(sorted(s) == index for s in per.values()), "the sets must hold the same parts"
    labels = np.array([per[ref][i][0] for i in index])
    types = np.array([per[ref][i][1] for i in index])
    rng = np.random.default_rng(0)
    report: dict = {"threshold": thr, "sets": {}}
    print(f"At the shipped threshold ({thr:.3f}); paired SEs over the same {len(index)} parts "
          f"({int((labels == 0).sum())} good):\n")
    print("| set | good rejected | caught | good rejected - ref (SE) | caught - ref (SE) | good parts' noise level: "
          "median / 90th / max | highlight share: median |\n|---|---|---|---|---|---|---|")
    flagged = {name: np.array([per[name][i][2] >= thr for i in index], float) for name, _ in sets}
    ref_rates = rates(labels, flagged[ref])
    good_idx = [i for i in index if per[ref][i][0] == 0]
    example = good_idx[int(np.argsort([per[ref][i][2] for i in good_idx])[len(good_idx) // 2])]  # median good part
    zmap = {}
    for name, spec in sets:
        data = spec.split(":")[1]
        sp = load_split(data, "test", cfg.priors, cfg.input_shape, roi=cfg.roi, frame_aspect=cfg.frame_aspect,
                        progress=False)
        good_rows = [sp.index.index(i) for i in good_idx]
        z = v.zmaps(sp.priors[good_rows])
        level, hidden = z.noise_level.numpy(), z.highlight_fraction.numpy()
        j = good_idx.index(example)
        zmap[name] = (sp.priors[good_rows[j], 0].numpy(), z.maps[j].numpy(), per[name][example][2])
        g, c = rates(labels, flagged[name])
        dg, dc = g - ref_rates[0], c - ref_rates[1]
        se = paired_se(labels, flagged[ref], flagged[name], rng)
        pct = np.percentile(level, [50, 90, 100])
        defective = sorted(set(types[labels == 1]))
        by_type = {t: float(flagged[name][(types == t) & (labels == 1)].mean()) for t in defective}
        report["sets"][name] = {"data": data, "good_rejected": g, "caught": c, "d_good_rejected": dg,
                                "d_good_rejected_se": se[0], "d_caught": dc, "d_caught_se": se[1],
                                "noise_level_pct_50_90_100": pct.tolist(), "highlight_share_median":
                                float(np.median(hidden)), "caught_by_type": by_type}
        print(f"| {name} | {100 * g:.1f} % | {100 * c:.1f} % | {100 * dg:+.1f} ({100 * se[0]:.1f}) | "
              f"{100 * dc:+.1f} ({100 * se[1]:.1f}) | {pct[0]:.2f} / {pct[1]:.2f} / {pct[2]:.2f} | "
              f"{np.median(hidden):.3f} |")
    print("\n| caught at the shipped threshold | " + " | ".join(n for n, _ in sets) + " |\n|---|"
          + "---|" * len(sets))
    for t in report["sets"][ref]["caught_by_type"]:
        print(f"| {t} | " + " | ".join(f"{100 * report['sets'][n]['caught_by_type'][t]:.0f} %" for n, _ in sets)
              + " |")
    json.dump(report, open(f"{out}.json", "w"), indent=1)

    fig = plt.figure(figsize=(10, 2.2 + 1.6 * len(sets)))
    ax = fig.add_subplot(len(sets) + 1, 1, 1)
    for name, _ in sets:
        s = np.sort([per[name][i][2] for i in good_idx])
        ax.plot(s, 1 - np.arange(len(s)) / len(s), label=name)
    ax.axvline(thr, color="k", lw=0.8, ls="--")
    ax.set_yscale("log")
    ax.set_xlabel("decision score of the good parts (dashed: shipped threshold)")
    ax.set_ylabel("share above")
    ax.legend(fontsize=7)
    for k, (name, _) in enumerate(sets):
        img, m, s = zmap[name]
        for j, (a, title) in enumerate(((img, "intensity"), (m, "variation map (0 to 10)"))):
            sub = fig.add_subplot(len(sets) + 1, 2, 2 * (k + 1) + j + 1)
            sub.imshow(a, cmap="gray" if j == 0 else "viridis", vmin=0, vmax=1.0 if j == 0 else 10)
            sub.set_title(f"{name}: good part {example}, {title}" + (f", score {s:.2f}" if j else ""), fontsize=7)
            sub.set_axis_off()
    fig.tight_layout()
    fig.savefig(f"{out}.png", dpi=70)


if __name__ == "__main__":
    main()
