"""After plan-3's reading, not deciding: where RADF-c's defective parts caught differ from RAD's on seed 1183, by type
and by the face the defect lies on (each file at its 1 % threshold, read from its eval.md, as read-2.py does).

Usage: python read-3-faces.py RAD_EVAL RADF_EVAL [NAME_A NAME_B]  (names default to RAD and RADF-c; plan 5 passes
WS-V and WS-F)"""
import importlib.util
import sys
from collections import defaultdict
from pathlib import Path

spec = importlib.util.spec_from_file_location("read_2", Path(__file__).with_name("read-2.py"))
read_2 = importlib.util.module_from_spec(spec)
spec.loader.exec_module(read_2)
report = read_2.report  # a report's 1 % threshold and scores, as read-2.py reads them

(t_a, a), (t_b, b) = report(sys.argv[1]), report(sys.argv[2])
name_a, name_b = sys.argv[3:5] if len(sys.argv) > 4 else ("RAD", "RADF-c")
rows = defaultdict(lambda: [0, 0, 0, 0, 0])  # parts, A caught, B caught, B only, A only
for i, r in a.items():
    if r["label"] != "1":
        continue
    ca, cb = float(r["score"]) > t_a, float(b[i]["score"]) > t_b
    row = rows[(r["defect_type"], r["face"])]
    for k, v in enumerate((1, ca, cb, cb and not ca, ca and not cb)):
        row[k] += v
print(f"| type | face | defective | {name_a} caught | {name_b} caught | caught by {name_b} only | by {name_a} only |")
print("|---|---|---|---|---|---|---|")
for (kind, face), row in sorted(rows.items()):
    print(f"| {kind} | {face} | " + " | ".join(str(v) for v in row) + " |")
