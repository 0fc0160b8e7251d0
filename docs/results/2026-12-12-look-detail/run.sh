#!/bin/bash
# screen: make model's recipe at --size 128 (1.33x the shipped detail), two look draws; resumable
set -euo pipefail
echo 19 > /proc/self/autogroup || true
cd /work/main
S=.venv/bin/station R=runs/size128
DATA=data/line-ef-train CAL=data/line-ef-val VAL=data/line-pv-val
MODEL=(--priors intensity --preset fast --fusion fused --batch-size 8 --seed 0 --device cpu --roi band --size 128)
[ -f $R/band/last.json ] || OMP_NUM_THREADS=2 $S train --data $DATA "${MODEL[@]}" --steps 30 --eval-every 30 --out $R/band
[ -f $R/band-variation.json ] || OMP_NUM_THREADS=2 $S variation --model $R/band/last --data $DATA --val-data $CAL \
    --decision variation --blur-copies 2.0 --out $R/band-variation
echo "variation done $(date +%T)"
look() { [ -f $R/look-$1.json ] || OMP_NUM_THREADS=1 $S residual --model $R/band-variation --data $DATA --val-data $CAL \
    --members 1 --steps 3000 --second-look --seed $1 --out $R/look-$1 > $R/look-$1.log 2>&1
  grep -qs '"outline": ' $R/look-$1.json || OMP_NUM_THREADS=1 $S shape --model $R/look-$1 --data $DATA --val-data $CAL --out $R/look-$1
  grep -qs '"blend": ' $R/look-$1.json || OMP_NUM_THREADS=1 $S blend --model $R/look-$1 --data $VAL --weight 0.25 --out $R/look-$1
  [ -f $R/look-$1.thr ] || { OMP_NUM_THREADS=1 $S threshold --model $R/look-$1 --data $VAL && touch $R/look-$1.thr; }
}
look 0 > $R/finish-0.log 2>&1 & look 2 > $R/finish-2.log 2>&1 & wait
echo "looks done $(date +%T)"
