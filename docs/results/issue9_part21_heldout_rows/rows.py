"""Issue 9, part 21: the classic rows of held-out comparisons, per task and arm, from each
experiment's ``evaluation.csv`` (the greedy episodes after training)::

    python docs/results/issue9_part21_heldout_rows/rows.py DIR [DIR ...]

Prints, per task: each arm's runs at the solved threshold, mean and lowest greedy return, and
the paired difference of the first arm ("general") over the second (bootstrap 95 %, 10,000
resamples of runs, generator seeded 0), with the runs where it is higher and lower.
"""

from __future__ import annotations

import csv
import sys
from collections import defaultdict
from pathlib import Path

import numpy as np

SOLVED = {"MountainCar-v0": -110.0, "Acrobot-v1": -100.0, "CartPole-v1": 475.0}


def greedy_means(folder: Path) -> dict[str, dict[str, dict[int, float]]]:
    """task -> strategy -> run -> mean greedy return."""
    returns: dict[tuple[str, str, int], list[float]] = defaultdict(list)
    with (folder / "evaluation.csv").open() as f:
        for row in csv.DictReader(f):
            returns[(row["task"], row["strategy"], int(row["run"]))].append(float(row["return"]))
    out: dict[str, dict[str, dict[int, float]]] = defaultdict(lambda: defaultdict(dict))
    for (task, strategy, run), values in returns.items():
        out[task][strategy][run] = float(np.mean(values))
    return out


def main(folders: list[str]) -> None:
    merged: dict[str, dict[str, dict[tuple[str, int], float]]] = defaultdict(
        lambda: defaultdict(dict)
    )
    for name in folders:
        for task, arms in greedy_means(Path(name)).items():
            for strategy, runs in arms.items():
                for run, value in runs.items():
                    merged[task][strategy][(name, run)] = value
    rng = np.random.default_rng(0)
    for task, arms in merged.items():
        line = SOLVED.get(task)
        print(f"{task} (solved {line})")
        for strategy in sorted(arms, key=lambda s: (s != "general", s)):
            values = np.array(list(arms[strategy].values()))
            solved = int((values >= line).sum()) if line is not None else "-"
            print(
                f"  {strategy:16s} runs {len(values):3d}  solved {solved}  "
                f"mean {values.mean():8.2f}  lowest {values.min():8.2f}"
            )
        names = sorted(arms)
        if "general" in arms and len(names) == 2:
            other = next(n for n in names if n != "general")
            keys = sorted(set(arms["general"]) & set(arms[other]))
            diff = np.array([arms["general"][k] - arms[other][k] for k in keys])
            boot = [rng.choice(diff, len(diff)).mean() for _ in range(10_000)]
            low, high = np.percentile(boot, [2.5, 97.5])
            print(
                f"  paired general - {other}: {diff.mean():+.2f} [{low:+.2f}, {high:+.2f}] "
                f"over {len(diff)} runs; higher {(diff > 0).sum()}, lower {(diff < 0).sum()}"
            )


if __name__ == "__main__":
    main(sys.argv[1:])
