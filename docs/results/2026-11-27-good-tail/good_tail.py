"""Which good parts the shipped model scores highest on its validation set, and what their scenes share.
Usage (from the repository root, after `station eval --model model/weights/default --data data/line-panel-val
--split val --no-synthetic --out runs/tail/eval-val`):
    .venv/bin/python docs/results/2026-11-27-good-tail/good_tail.py runs/tail/eval-val data/line-panel-val
Prints the share of good parts above the 5 % and 1 % thresholds by belt finish, stray light and plug finish, and
draws the six highest-scoring good parts (priors and the variation model's z map) into good-tail.png beside it."""

from __future__ import annotations

import csv
import json
import sys
from pathlib import Path

import numpy as np

from model.draem.metrics import false_reject_threshold


def scenes(ev: str, data: str) -> list[dict]:
    """Each scored part of ``ev`` with the scene draws that could make a good part look unusual."""
    out = []
    for r in csv.DictReader(open(Path(ev) / "scores.csv")):
        p = json.loads((Path(data) / "samples" / f"{int(r['index']):06d}" / "params.json").read_text())
        s = p["scene"]
        out.append({"index": int(r["index"]), "label": int(r["label"]), "score": float(r["score"]),
                    "glossy_belt": s["background"]["material"]["type"] != "diffuse",
                    "stray": float(s["light"]["intensity"]), "plug_alpha": float(s["materials"]["metal"]["alpha"])})
    return out


def table(parts: list[dict], t5: float, t1: float) -> None:
    good = [g for g in parts if g["label"] == 0]
    groups = [("glossy belt", lambda g: g["glossy_belt"]), ("matte belt", lambda g: not g["glossy_belt"]),
              ("stray light > 0.3", lambda g: g["stray"] > 0.3), ("stray light <= 0.3", lambda g: g["stray"] <= 0.3),
              ("polished plug (roughness < 0.2)", lambda g: g["plug_alpha"] < 0.2),
              ("rougher plug (>= 0.2)", lambda g: g["plug_alpha"] >= 0.2), ("all", lambda g: True)]
    print("| good parts | n | above the 5 % threshold | above the 1 % threshold |\n|---|---|---|---|")
    for name, f in groups:
        sub = [g for g in good if f(g)]
        a5, a1 = (100 * np.mean([g["score"] > t for g in sub]) for t in (t5, t1))
        print(f"| {name} | {len(sub)} | {a5:.1f} % | {a1:.1f} % |")


def draw(model: str, data: str, want: list[int], out: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import torch

    from model.draem.checkpoint import load_checkpoint
    from station.evaluation import model_split

    ck = load_checkpoint(model)
    sp = model_split(ck, model, data, "val")
    x = sp.priors[[list(sp.index).index(i) for i in want]]
    with torch.no_grad():
        v = ck.detector.eval().variation.zmaps(x, signed=False)
    fig, ax = plt.subplots(len(want), 3, figsize=(10, 2.0 * len(want)))
    for r, i in enumerate(want):
        ax[r, 0].imshow(x[r, 0].numpy(), cmap="gray")
        ax[r, 1].imshow(x[r, 1].numpy(), cmap="viridis")
        ax[r, 2].imshow(v.maps[r].numpy(), cmap="magma")
        ax[r, 0].set_title(f"good part {i}: intensity", fontsize=7)
        ax[r, 1].set_title("DoLP", fontsize=7)
        ax[r, 2].set_title(f"variation z map (score {float(v.scores[r]):.1f} robust SD)", fontsize=7)
        for a in ax[r]:
            a.axis("off")
    fig.tight_layout()
    fig.savefig(out, dpi=70)


def main() -> None:
    ev, data = sys.argv[1:3]
    report = json.loads((Path(ev) / "eval.json").read_text())
    model = report["model"]
    parts = scenes(ev, data)
    good = sorted((g for g in parts if g["label"] == 0), key=lambda g: -g["score"])
    t5, t1 = (false_reject_threshold(np.array([g["score"] for g in good]), q) for q in (0.05, 0.01))
    table(parts, t5, t1)
    draw(model, data, [g["index"] for g in good[:6]], Path(__file__).parent / "good-tail.png")


if __name__ == "__main__":
    main()
