import copy, numpy as np, matplotlib; matplotlib.use('Agg'); import matplotlib.pyplot as plt
from model.draem.checkpoint import load_checkpoint
from station.evaluation import model_split
M="model/weights/default"; ck=load_checkpoint(M); vm=copy.deepcopy(ck.detector.variation); vm.second_look.calibration[0]=np.inf
sp=model_split(ck,M,"data/line-panel-val","val")
idx=list(sp.index); want=[540,218,72,297,585,457]
rows=[idx.index(w) for w in want]
x=sp.priors[rows].float(); o=vm.zmaps(x,signed=True)
fig,ax=plt.subplots(len(rows),5,figsize=(20,2.2*len(rows)))
for r,(i,m,s,j) in enumerate(zip(want,o.maps.numpy(),o.signed.numpy(),o.judged.numpy())):
    xi=x[r].numpy(); w=vm.register(xi, vm.features(xi))
    ax[r,0].imshow(w[0]); ax[r,0].set_title(f'{i} logI registered')
    ax[r,1].imshow(m); ax[r,1].set_title('window map')
    for c in (0,2,3): ax[r,{0:2,2:3,3:4}[c]].imshow(s[c],cmap='RdBu',vmin=-8,vmax=8); ax[r,{0:2,2:3,3:4}[c]].set_title(f'signed z c{c}')
for a in ax.flat: a.axis('off')
plt.tight_layout(); plt.savefig('runs/r48/tail.png',dpi=60)
