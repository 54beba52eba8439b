#!/bin/bash
# Part 35 round 3's gate for OVERRIDES (WORKER=0 or 1 as $1): half the dev mazes, then half of
# MountainCar seeds 10-49 and CartPole seeds 0-9.
cd "$(dirname "$0")"
W=$1
MAZES=(corridors "forest:seed=0" "forest:seed=1,count=70,radius_max=8,gap=11" "forest:seed=2,count=70,radius_max=8,gap=11" "forest:seed=3,count=70,radius_max=8,gap=11" "maze:seed=0" "maze:seed=1,rows=8,cols=8,cell=37.5" "maze:seed=2,rows=8,cols=8,cell=37.5" "maze:seed=3,rows=8,cols=8,cell=37.5" open paper_narrow "rooms:seed=0" "rooms:seed=1,door=14,loops=0" "rooms:seed=2,door=14,loops=0" "rooms:seed=3,door=14,loops=0" "serpentine:seed=0" "serpentine:seed=1,corridors=5,width=50")
i=0
for m in "${MAZES[@]}"; do
  if [ $((i % 2)) -eq "$W" ]; then python maze_runs.py "maze:$m" r3_mazes.jsonl 10 11; fi
  i=$((i + 1))
done
MC=(); for s in $(seq $((10 + W)) 2 49); do MC+=("$s"); done
python ../issue9_part34_dev/override_runs.py MountainCar-v0 r3_mc.jsonl "${MC[@]}"
CP=(); for s in $(seq "$W" 2 9); do CP+=("$s"); done
python ../issue9_part34_dev/override_runs.py CartPole-v1 r3_cp.jsonl "${CP[@]}"
echo done
