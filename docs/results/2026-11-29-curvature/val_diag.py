import numpy as np, torch, sys
from model.draem.checkpoint import load_checkpoint
from model.draem.second_look import SecondLook
from model.draem.metrics import auroc
from station.evaluation import model_split
for m in sys.argv[1:]:
    ck = load_checkpoint(m)
    vm = ck.detector.variation
    s = model_split(ck, m, "data/line-pv-val", "val")
    y, t = np.asarray(s.label), np.array(s.defect_type)
    with torch.no_grad():
        full = vm.zmaps(s.priors).scores.numpy()
        vm.second_look = SecondLook()
        win = vm.zmaps(s.priors).scores.numpy()
    for name, sc in (("window", win), ("with look", full)):
        th = np.percentile(sc[y == 0], 99)
        print(m, name, "auroc %.3f caught@1%% %.3f dents %.3f" % (auroc(y, sc), (sc[y == 1] > th).mean(),
              (sc[t == "dent"] > th).mean()), flush=True)
