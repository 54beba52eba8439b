#!/bin/bash
# Part 33 round 2: CUT=2 on the 12 forests, agent seed 4 + W (W = 0 or 1).
cd "$(dirname "$0")/../../.."
export PYTHONPATH=$PWD
D=docs/results/issue9_part33_dev
FORESTS=()
for s in 4 5 6 7 8 9 10 11 12 13 14 15; do FORESTS+=("forest:seed=$s"); done
CUT=2 python $D/cut_runs.py forests $D/r2_forests_cut2.jsonl $((4 + $1)) "${FORESTS[@]}"
echo done
