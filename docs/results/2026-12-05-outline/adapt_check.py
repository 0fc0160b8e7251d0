"""A feature check of `station adapt` with the outline check (nothing selected on it): the shipped file adapted on the
first 300 parts of data/line-pv-val (runs/outline/adapted, as docs/results/2026-12-05-adapt-shape.md adapted it), and
the shipped file, each at its own threshold, on the development flash set (seed 1201) and the validation warps (seed
1199): flash and warps caught, good parts rejected. Run from the repository's root after
`station adapt --model model/weights/default --good data/line-pv-val --split val --limit 300 --out
runs/outline/adapted`."""

from model.draem.adapt import image_scores
from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

for path in ("model/weights/default", "runs/outline/adapted"):
    ck = load_checkpoint(path)
    line = [f"{path}: threshold {ck.threshold:.4f}"]
    for data, split in (("data/flash-dev-1201", "test"), ("data/warp-val-1199", "val")):
        sp = model_split(ck, path, data, split)
        rej, lab = image_scores(ck.detector, sp.priors) > ck.threshold, sp.label.numpy() == 1
        line.append(f"{data}: {int(rej[lab].sum())} of {int(lab.sum())} defective caught, "
                    f"{int(rej[~lab].sum())} of {int((~lab).sum())} good rejected")
    print("; ".join(line), flush=True)
