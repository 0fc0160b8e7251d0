"""After the reads (not in either plan): the shipped file's two findings on good parts, the window's w (with its
checks, without the look) and the look network's f, each over its own blend threshold (t_w, t_f), on the validation
set's good parts and on seed 1240's good parts as built, through vignetting alone and through the whole lens chain.
Does the look's finding on a line's good parts tell a lens the renders did not have (a monitor's signal)? Writes every
part's f / t_f (good and defective, with labels) to findings.npz beside it.

    PYTHONPATH=. .venv/bin/python docs/results/2026-12-07-blend-otherwise/findings.py > .../findings.txt
"""
from pathlib import Path

import numpy as np

from model.draem.checkpoint import load_checkpoint
from model.draem.with_variation import blend_inputs
from station.evaluation import model_split

MODEL = "model/weights/default"
SETS = (("validation (data/line-pv-val, val)", "data/line-pv-val", "val"),
        ("seed 1240 as built", "data/bo-built-1240", "test"),
        ("seed 1240, vignetting alone", "data/bo-vignette-1240", "test"),
        ("seed 1240, the whole lens chain", "data/bo-allff-1240", "test"))


def main() -> None:
    arrays = {}
    ck = load_checkpoint(MODEL)
    blend = ck.detector.residual.blend.double().numpy()
    t_w, t_f = float(blend[1]), float(blend[2])
    print(f"t_w {t_w:.3f}, t_f {t_f:.3f} (window units)")
    print("| good parts of | n | w / t_w: median | 90th | f / t_f: median | 90th | share with f > t_f |")
    print("|---|---|---|---|---|---|---|")
    for label, data, split in SETS:
        sp = model_split(ck, MODEL, data, split)
        lab = sp.label.numpy()
        around = None if sp.around is None else sp.around.float()
        w_all, f_all = blend_inputs(ck.detector, sp.priors.float(), around=around)
        arrays[f"{data}:{split}:label"], arrays[f"{data}:{split}:f"] = lab, f_all / t_f
        good = lab == 0
        w, f = w_all[good] / t_w, f_all[good] / t_f
        print(f"| {label} | {good.sum()} | {np.median(w):.2f} | {np.quantile(w, 0.9):.2f} | {np.median(f):.2f} | "
              f"{np.quantile(f, 0.9):.2f} | {(f > 1).mean():.1%} |", flush=True)
    np.savez_compressed(Path(__file__).with_name("findings.npz"), **arrays)


if __name__ == "__main__":
    main()
