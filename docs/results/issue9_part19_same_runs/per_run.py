"""Per-run greedy returns of one task in experiment folders, both arms side by side::

    python docs/results/issue9_part19_same_runs/per_run.py TASK STRATEGY BASELINE FOLDER...

For each folder (``evaluation.csv``) prints, per run, the mean greedy return of STRATEGY and of
BASELINE, then the runs solved and the means (issue 9, part 19's report in docs/results.md).
"""

from __future__ import annotations

import csv
import sys
from collections import defaultdict
from pathlib import Path

SOLVED = {"CartPole-v1": 475.0, "MountainCar-v0": -110.0, "Acrobot-v1": -100.0}


def main(task: str, strategy: str, baseline: str, folders: list[str]) -> None:
    for folder in folders:
        returns: dict[tuple[str, int], list[float]] = defaultdict(list)
        with (Path(folder) / "evaluation.csv").open() as f:
            for row in csv.DictReader(f):
                if row["task"] == task:
                    returns[(row["strategy"], int(row["run"]))].append(float(row["return"]))
        print(folder)
        for arm in (strategy, baseline):
            means = [sum(v) / len(v) for (s, _), v in sorted(returns.items()) if s == arm]
            solved = sum(m >= SOLVED[task] for m in means)
            shown = ", ".join(f"{m:.1f}" for m in means)
            print(f"  {arm}: {shown}; {solved} of {len(means)}, mean {sum(means) / len(means):.1f}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:])
