"""Detection by face for each camera of seed 1178 at its own threshold, the faces taken from the side twins'
records (rendered after scratches and stains began to record their normal; twins share every draw, so the line
camera's parts carry the same defects): ``station.defect_face.by_face`` over each camera's own labels.

    python faces.py > faces.md   (from the repository root)
"""
import csv
import json

from station.benchmarks.report import markdown_table
from station.defect_face import COLUMNS, by_face

for cam, run in (("line camera", "runs/check-1178/eval-line"), ("side camera", "runs/check-1178/eval-side")):
    rows = list(csv.DictReader(open(f"{run}/scores.csv")))
    records = [json.load(open(f"data/sw-heldout-1178/samples/{int(r['index']):06d}/params.json")).get("defect")
               for r in rows]
    threshold = json.load(open(f"{run}/eval.json"))["threshold"]
    table = by_face(records, [int(r["label"]) for r in rows], [float(r["score"]) for r in rows], threshold,
                    [r["defect_type"] for r in rows])
    print(f"{cam} ({run}, its own threshold {threshold:.4f}):\n\n{markdown_table(table, COLUMNS)}\n")
