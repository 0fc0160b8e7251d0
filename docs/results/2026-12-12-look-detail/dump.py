"""Per part of a set, what each file's look blend reads (../2026-12-12-look-ensemble/dump.py's arrays), for several
files of one input size, the set loaded once. Usage: dump.py SET SPLIT NAME MODEL=OUT_DIR... (writes
OUT_DIR/NAME.npz for each)."""

import importlib.util
import sys
from pathlib import Path

import numpy as np

from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split

_spec = importlib.util.spec_from_file_location(
    "ensemble_dump", Path(__file__).parent.parent / "2026-12-12-look-ensemble/dump.py")
ensemble_dump = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ensemble_dump)

data, split, name, *pairs = sys.argv[1:]
files = [p.split("=", 1) for p in pairs]
cks = [load_checkpoint(m) for m, _ in files]
assert len({ck.detector.config.input_shape for ck in cks}) == 1, "one input size per call"
sp = model_split(cks[0], files[0][0], data, split)
for ck, (_, out) in zip(cks, files, strict=True):
    Path(out).mkdir(parents=True, exist_ok=True)
    np.savez(Path(out) / f"{name}.npz", **ensemble_dump.arrays(ck.detector, sp))
    print(out, name, len(sp.label))
