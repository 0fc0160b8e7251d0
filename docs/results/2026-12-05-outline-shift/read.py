"""plan.md's table: B (the outline check off) beside S (the shipped file) per shift of `station bench shift`, from
shift-B.json and shift-S.json: good parts rejected at each file's own threshold (count of the set's good parts),
defective parts caught and good parts rejected at the threshold that rejects 1 % of good validation parts, image
AUROC. Run in this folder: python read.py > read.txt"""

import json

b, s = (json.load(open(f"shift-{f}.json")) for f in "BS")
good = b["good_parts"]
assert good == s["good_parts"] and b["parts"] == s["parts"]
print(f"{b['data']}: {b['parts']} parts, {good} good; thresholds B {b['threshold']}, S {s['threshold']}; "
      f"1 % and 5 % points from {b['val_data']}")
print(f"{'shift':<16}{'good rejected, own threshold':>30}{'caught at 1 %':>18}{'good rejected at 1 %':>24}"
      f"{'image AUROC':>16}")
print(f"{'':<16}{'B':>15}{'S':>15}{'B':>9}{'S':>9}{'B':>12}{'S':>12}{'B':>8}{'S':>8}")
for rb, rs in zip(b["rows"], s["rows"], strict=True):
    assert rb["shift"] == rs["shift"]
    own = [round(r["good_rejected_own"] * good) for r in (rb, rs)]
    print(f"{rb['shift']:<16}{own[0]:>9} ({100 * own[0] / good:.1f}%){own[1]:>6} ({100 * own[1] / good:.1f}%)"
          f"{100 * rb['caught_1%']:>8.1f}%{100 * rs['caught_1%']:>8.1f}%"
          f"{100 * rb['good_rejected_1%']:>11.1f}%{100 * rs['good_rejected_1%']:>11.1f}%"
          f"{rb['image_auroc']:>8.3f}{rs['image_auroc']:>8.3f}")
