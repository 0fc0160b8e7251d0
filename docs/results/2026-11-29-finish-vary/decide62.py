"""Rule 62 (plan.md): K3 and F on S, G and R at each file's own threshold, paired over the same parts.
Usage: python decide62.py K3_PATTERN F_PATTERN [--f-threshold SIDECAR], each pattern an eval report folder with {}
for S, G or R (e.g. runs/c61/eval-K3-{} runs/r62/eval-F-{}63 for the screen). --f-threshold: F's threshold from that
checkpoint sidecar instead of the reports' (rule 63: F thresholded again, its scores unchanged)."""
import json
import sys
from pathlib import Path

import numpy as np

from model.draem.metrics import auroc, paired_auroc_gains
from station.eval_compare import read_scores

BOOT = 1000
rng = np.random.default_rng(0)
pattern = {"K3": sys.argv[1], "F": sys.argv[2]}
f_threshold = (float(json.loads(Path(sys.argv[4]).read_text())["threshold"])
               if sys.argv[3:4] == ["--f-threshold"] else None)


def read(name, k):
    """(labels, decision scores, defect types) in dataset order and the file's threshold."""
    d = Path(pattern[name].format(k))
    scores = read_scores(d)
    idx = sorted(scores)
    th = float(json.loads((d / "eval.json").read_text())["threshold"])
    return (np.array([scores[i][0] for i in idx]), np.array([scores[i][2] for i in idx]),
            np.array([scores[i][1] for i in idx]), f_threshold if name == "F" and f_threshold is not None else th)


def figures(y, s, th):
    return auroc(y, s), float((s[y == 0] > th).mean()), float((s[y == 1] > th).mean())


def boot_se(fn):
    out = [v for v in (fn(rng.integers(n, size=n)) for _ in range(BOOT)) if v is not None]
    return float(np.std(out))


data = {(f, k): read(f, k) for f in pattern for k in "SGR"}
y, _, types, _ = data["K3", "S"]
n = len(y)
for key, (y1, *_rest) in data.items():
    assert (y1 == y).all(), f"{key}: the sets' parts differ"
good = int((y == 0).sum())

print("| file | set | image AUROC | good parts rejected | defective parts caught | AUROC change (SE) |"
      " good rejected change, points (SE) | holds (rule 35's bar) |")
print("|---|---|---|---|---|---|---|---|")
held = {}
for f in pattern:
    _, s0, _, th = data[f, "S"]
    a0, g0, c0 = figures(y, s0, th)
    print(f"| {f} | S | {a0:.3f} | {100 * g0:.1f} % ({round(g0 * good)}) | {100 * c0:.1f} % | | | |")
    for k in "GR":
        s1 = data[f, k][1]
        a1, g1, c1 = figures(y, s1, th)

        def d_good(b, s1=s1, s0=s0, th=th):
            g = y[b] == 0
            return float((s1[b][g] > th).mean() - (s0[b][g] > th).mean())

        se_auroc = paired_auroc_gains(y, types, s0, s1)[0]["se"]  # the project's paired bootstrap
        held[f, k] = (a0 - a1 < 0.03) and (g1 <= 2 * g0 + 0.02)
        print(f"| {f} | {k} | {a1:.3f} | {100 * g1:.1f} % ({round(g1 * good)}) | {100 * c1:.1f} % |"
              f" {a1 - a0:+.3f} ({se_auroc:.3f}) | {100 * (g1 - g0):+.1f} ({100 * boot_se(d_good):.1f}) |"
              f" {'yes' if held[f, k] else 'no'} |")

(_, k3, _, tk), (_, fs, _, tf) = data["K3", "S"], data["F", "S"]
d_caught = float((fs[y == 1] > tf).mean() - (k3[y == 1] > tk).mean())
gain = paired_auroc_gains(y, types, k3, fs)[0]  # the project's paired bootstrap (good and defective apart)
d_auc, se_a = gain["gain"], gain["se"]
se_c = boot_se(lambda b: float((fs[b][y[b] == 1] > tf).mean() - (k3[b][y[b] == 1] > tk).mean()))
rejected = {f: sum(int((data[f, k][1][y == 0] > data[f, "S"][3]).sum()) for k in "GR") for f in pattern}
print()
print("| S, by type (caught at each file's threshold) | parts | K3 | F |")
print("|---|---|---|---|")
for t in sorted(set(types[y == 1])):
    m = (y == 1) & (types == t)
    print(f"| {t} | {int(m.sum())} | {100 * (k3[m] > tk).mean():.0f} % | {100 * (fs[m] > tf).mean():.0f} % |")
print()
print(f"S, F against K3: caught {100 * d_caught:+.1f} points (SE {100 * se_c:.1f}), image AUROC {d_auc:+.3f}"
      f" (SE {se_a:.3f})")
print(f"G and R together, good parts rejected: K3 {rejected['K3']}, F {rejected['F']} (of {2 * good})")
c1 = d_caught >= -0.02 and d_auc >= -0.01
c2 = rejected["F"] < rejected["K3"]
c3 = held["F", "G"] and held["F", "R"]
c4 = (fs[y == 0] > tf).mean() - (k3[y == 0] > tk).mean() <= 0.02
print(f"rule 62: 1 (S) {'yes' if c1 else 'no'}; 2 (fewer rejected under G and R) {'yes' if c2 else 'no'};"
      f" 3 (F holds under G and R) {'yes' if c3 else 'no'} -> {'F replaces K3' if c1 and c2 and c3 else 'K3 stays'}")
print(f"rule 63 adds 4 (S: at most 2 points more of good parts rejected) {'yes' if c4 else 'no'} ->"
      f" {'F63 replaces K3' if c1 and c2 and c3 and c4 else 'K3 stays'}")
print(f"screen: {'passes' if rejected['F'] < rejected['K3'] and d_caught >= -0.03 else 'fails'}"
      f" (fewer rejected under G and R, and at most 3 points fewer caught on S)")
