"""The fireflies page's table: for each (file, set, station eval folder), good parts rejected and defective parts
caught at the validation set's 1 % threshold as each eval's note states it (the shipped file's threshold and the file
before's are those points; rule 56's reports ran when that file's threshold was its 5 % point), and image AUROC.
Usage: python table.py NAME=FOLDER ..."""
import json
import re
import sys
from pathlib import Path

from station.eval_compare import read_scores

print("| file, set | good parts rejected at 1 % | defective parts caught at 1 % | image AUROC |")
print("|---|---|---|---|")
for arg in sys.argv[1:]:
    name, folder = arg.split("=", 1)
    d = Path(folder)
    ev = json.loads((d / "eval.json").read_text())
    th = float(re.search(r"1 % -> ([0-9.]+)", ev["industrial_note"]).group(1))  # the validation set's 1 % point
    scores = read_scores(d).values()
    good = [s for label, _, s in scores if label == 0]
    bad = [s for label, _, s in scores if label == 1]
    rej = sum(s > th for s in good)
    caught = sum(s > th for s in bad)
    auroc = next(r for r in ev["industrial"] if r["type"] == "all")["image_auroc"]
    print(f"| {name} | {100 * rej / len(good):.1f} % ({rej} of {len(good)}) | {100 * caught / len(bad):.1f} % |"
          f" {auroc:.3f} |")
