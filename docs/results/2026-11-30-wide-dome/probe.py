"""Check 68's probe (plan.md): samples of data/sv-pv-val rendered again with [view] keys or spp overridden, every
other draw the same; saves each frame's S0, the rendered S0 (truth), object mask, part index and normals.

Usage (repository root): python docs/results/2026-11-30-wide-dome/probe.py TAG '{"flat_dome_width_m": 0.36}' 463,119
Writes /tmp/probe/TAG-INDEX.npz."""
import sys, json, copy, time, numpy as np
from sim.dataset import DatasetSpec, prepare, generate_sample
from model.priors.mosaic import normalize_mosaic
from model.priors.demosaic import mosaic_to_stokes
m = json.load(open("data/sv-pv-val/manifest.json"))
cfg = copy.deepcopy(m["config"])
tag, over = sys.argv[1], json.loads(sys.argv[2]); idxs=[int(a) for a in sys.argv[3].split(",")]
for k, v in over.items():
    if k == "spp": cfg["spp"] = v
    else: cfg["view"][k] = v
spec = DatasetSpec.from_dict(cfg); model = prepare(spec)
for i in idxs:
    t=time.time(); s = generate_sample(spec, model, i)
    s0,_,_ = mosaic_to_stokes(normalize_mosaic(s.raw).data)
    np.savez_compressed(f"/tmp/probe/{tag}-{i}.npz", s0=s0, mask=s.object_mask, pi=s.part_index, normal=s.normal, truth=s.s0)
    print(tag, i, f"{time.time()-t:.1f}s", flush=True)
