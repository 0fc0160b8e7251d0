"""After plan 3's read (nothing chosen on it): would the station's drift monitor have warned of a turned camera?
Each set's frames in order through ``station.drift.DriftMonitor`` with the shipped file's trained range, as the
station feeds it; prints the first warning and its frame, or that none came.

Usage: python drift.py SET:SPLIT ... (run from the repository's root)."""
import sys

from model.draem.checkpoint import load_checkpoint
from station.datasets import load_split
from station.drift import DriftMonitor, trained_range

ck = load_checkpoint("model/weights/default")
cfg = ck.detector.config
trained = trained_range(ck.meta)
assert trained is not None
for arg in sys.argv[1:]:
    path, split = arg.split(":")
    sp = load_split(path, split, cfg.priors, cfg.input_shape, roi=cfg.roi, frame_aspect=cfg.frame_aspect,
                    dome_segments=cfg.dome_segments, progress=False)
    monitor = DriftMonitor(trained)
    said = [(i, text) for i, st in enumerate(sp.frame_stats) if (text := monitor.update(st))]
    print(f"{arg}: {len(said)} warnings over {len(sp.frame_stats)} frames" + (f"; first at frame {said[0][0]}: "
                                                                        f"{said[0][1]}" if said else ""))
