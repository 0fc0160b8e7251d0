"""Three good parts the shipped file rejects on the 0.3 mm chamfered set: the sharp render (left) and the chamfered
one (right), intensity with the file's heatmap in red. Run from the repository root:
python docs/results/2026-12-02-sensor-response/edge_heat.py -> edge-heatmaps.jpg"""
import csv
from pathlib import Path

import cv2
import numpy as np

from model.draem.predictor import load_predictor
from model.priors.api import compute_priors

HERE = Path(__file__).parent
p = load_predictor("model/weights/default", device="cpu", precision="fp32")
rows = list(csv.DictReader(open(HERE / "eval-edge03-1184" / "scores.csv")))
good = [int(r["index"]) for r in rows if r["label"] == "0" and float(r["score"]) > p.threshold][:3]
tiles = []
for i in good:
    for d in ("line-panel-heldout-1184", "edge03-heldout-1184"):
        raw = cv2.imread(f"data/{d}/samples/{i:06d}/raw.png", cv2.IMREAD_UNCHANGED)
        maps = compute_priors(raw, priors=p.priors, bit_depth=12)
        heat = p.predict(maps).heatmap
        inten = np.clip(maps["intensity"] / np.quantile(maps["intensity"], 0.99), 0, 1)
        rgb = np.stack([inten, inten, np.maximum(inten, heat)], -1)  # BGR: the heatmap in red
        tiles.append((rgb[100:380, 100:540] * 255).astype(np.uint8))
im = np.concatenate([np.concatenate(tiles[k:k + 2], 1) for k in range(0, len(tiles), 2)], 0)
cv2.imwrite(str(HERE / "edge-heatmaps.jpg"), cv2.resize(im, None, fx=0.75, fy=0.75, interpolation=cv2.INTER_AREA),
            [cv2.IMWRITE_JPEG_QUALITY, 80])
print("good parts", good)
