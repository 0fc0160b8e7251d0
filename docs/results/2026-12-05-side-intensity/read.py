"""plan.md's readings 1-2: each side file alone and each pair at its split, per set, pooled as built (seeds 1196 and
1197) and rendered otherwise (seed 1193 with a GGX lobe and with a duller plastic), and SI's pair minus SA's pair per
part (paired SE); and the same for its addenda (seed 1196's broken edges; seed 1195's kinds nobody rendered). The
decisions are ``station compare --split``'s (``station.eval_compare.pair_decisions``); a frame a camera would not judge
rejects the part.

    cd docs/results/2026-12-05-side-intensity && PYTHONPATH=../../.. ../../../.venv/bin/python read.py > read.txt
"""
import json
from pathlib import Path

import numpy as np

from station.eval_compare import pair_decisions

HERE = Path(__file__).parent
GROUPS = {"as built (1196 + 1197)": ("1196", "1197"), "rendered otherwise (GGX + duller, 1193)": ("ggx", "rough"),
          "broken edges (1196 chamfered + rounded; addendum)": ("e3", "r3"),
          "kinds nobody rendered (1195; addendum 2)": ("nk",)}


def decisions(tag: str, side: str) -> dict[str, np.ndarray]:
    """Per part of set ``tag``: defective, front face, the side file alone, the pair at the side file's split."""
    d = pair_decisions(HERE / "eval" / f"line-{tag}", HERE / "eval" / f"{side}-{tag}", HERE / f"split-{side}.json")
    _, alone, pair = d.rules.values()
    return {"y": d.defective, "front": d.faces == "front", "alone": alone, "pair": pair}


out = {}
for group, tags in GROUPS.items():
    print(f"## {group}")
    rows = {}
    for side in ("SA", "SI"):
        d = [decisions(t, side) for t in tags]
        cat = {k: np.concatenate([x[k] for x in d]) for k in d[0]}
        y = cat["y"]
        rows[side] = cat
        for t, x in zip(tags, d, strict=True):
            print(f"  {side} seed/set {t}: side alone {int(x['alone'][~x['y']].sum())} of {int((~x['y']).sum())} good "
                  f"rejected, front faces {int(x['alone'][x['y'] & x['front']].sum())} of "
                  f"{int((x['y'] & x['front']).sum())} caught; pair {int(x['pair'][~x['y']].sum())} good rejected, "
                  f"{int(x['pair'][x['y']].sum())} of {int(x['y'].sum())} caught")
        print(f"  {side} pooled: side alone {int(cat['alone'][~y].sum())} of {int((~y).sum())} good rejected; pair "
              f"{int(cat['pair'][~y].sum())} of {int((~y).sum())} good rejected "
              f"({100 * cat['pair'][~y].mean():.1f} %), {int(cat['pair'][y].sum())} of {int(y.sum())} caught "
              f"({100 * cat['pair'][y].mean():.1f} %)")
    y = rows["SA"]["y"]
    diff = rows["SI"]["pair"][y].astype(float) - rows["SA"]["pair"][y].astype(float)
    se = diff.std(ddof=1) / np.sqrt(diff.size)
    print(f"  SI pair minus SA pair, defective caught: {100 * diff.mean():+.1f} points (paired SE {100 * se:.1f}); "
          f"good rejected {int(rows['SI']['pair'][~y].sum()) - int(rows['SA']['pair'][~y].sum()):+d}")
    out[group] = {side: {"good": int((~y).sum()), "good_rejected": int(r["pair"][~y].sum()),
                         "defective": int(y.sum()), "caught": int(r["pair"][y].sum()),
                         "side_alone_good_rejected": int(r["alone"][~y].sum())} for side, r in rows.items()}
    out[group]["SI_minus_SA_points"] = 100 * float(diff.mean())
    out[group]["SE"] = 100 * float(se)
(HERE / "read.json").write_text(json.dumps(out, indent=1) + "\n")
