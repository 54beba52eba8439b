"""One line per finished run of a results folder (issue 9, part 4):

    python docs/results/issue9_part4/summarise.py results/maze_dev4

AUC = mean steps per episode over the run, final = mean steps of the last 100 episodes (each
also over the layout's optimum), goals = episodes that reached the goal, first = the first
such episode (0-based), the tree's leaves after episode 100 and at the end, the run's CPU
seconds and its greedy evaluation's successes.
"""

from __future__ import annotations

import csv
import glob
import json
import sys
from pathlib import Path


def main() -> None:
    root = sys.argv[1]
    for path in sorted(glob.glob(root + "/runs/*/*[0-9].json")):
        meta = json.loads(Path(path).read_text())
        rows = list(csv.DictReader(Path(path[:-5] + ".csv").read_text().splitlines()))
        steps = [int(r["steps"]) for r in rows]
        goals = sum(r["success"] == "1" for r in rows)
        final = sum(steps[-100:]) / 100
        auc = sum(steps) / len(steps)
        first = next((i for i, r in enumerate(rows) if r["success"] == "1"), None)
        evals = list(csv.DictReader(Path(path[:-5] + ".eval.csv").read_text().splitlines()))
        optimum = meta["optimal_steps"]
        print(
            f"{meta['task']:42s} {meta['strategy']:20s} opt {optimum:4.0f} "
            f"AUC {auc:5.0f} ({auc / optimum:.2f}x) final {final:5.0f} ({final / optimum:.2f}x) "
            f"goals {goals:3d} first {first} leaves@100 {rows[99]['leaves']} "
            f"end {rows[-1]['leaves']} cpu {meta['meta']['cpu_time_s']:.0f} "
            f"eval {sum(e['success'] == '1' for e in evals)}/{len(evals)}"
        )


if __name__ == "__main__":
    main()
