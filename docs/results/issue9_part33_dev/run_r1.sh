#!/bin/bash
# Part 33 round 1: half the runs per worker (WORKER=0 or 1); both arms for each piece.
cd "$(dirname "$0")/../../.."
export PYTHONPATH=$PWD
D=docs/results/issue9_part33_dev
W=$1
FORESTS=()
for s in 4 5 6 7 8 9 10 11 12 13 14 15; do FORESTS+=("forest:seed=$s"); done
MAZES=(corridors "forest:seed=0" "forest:seed=1,count=70,radius_max=8,gap=11" "forest:seed=2,count=70,radius_max=8,gap=11" "forest:seed=3,count=70,radius_max=8,gap=11" "maze:seed=0" "maze:seed=1,rows=8,cols=8,cell=37.5" "maze:seed=2,rows=8,cols=8,cell=37.5" "maze:seed=3,rows=8,cols=8,cell=37.5" open paper_narrow "rooms:seed=0" "rooms:seed=1,door=14,loops=0" "rooms:seed=2,door=14,loops=0" "rooms:seed=3,door=14,loops=0" "serpentine:seed=0" "serpentine:seed=1,corridors=5,width=50")
SEED=$((4 + W))
for cut in 0 1; do CUT=$cut python $D/cut_runs.py forests $D/r1_forests_cut$cut.jsonl $SEED "${FORESTS[@]}"; done
i=0
for m in "${MAZES[@]}"; do
  if [ $((i % 2)) -eq "$W" ]; then
    for cut in 0 1; do CUT=$cut python $D/cut_runs.py mazes "maze:$m" $D/r1_mazes_cut$cut.jsonl 10 11; done
  fi
  i=$((i + 1))
done
echo done
