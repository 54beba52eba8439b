"""Part 38, round 2: the learning curve of today's general preset, with TreeConfig overrides.

    OVERRIDES='{"novelty_cells": 4}' python learning_curve.py TASK OUT SEED [SEED ...]

1,000 episodes from reset seed = agent seed; one JSON line per seed with the first episode that
reached the goal and the mean steps per episode over the run, its first 300 and its last 100.
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

from first_success import OVERRIDES, train  # this folder's script, on sys.path when run


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, out = argv[1], Path(argv[2])
    for seed in map(int, argv[3:]):
        history = train(task, seed, 1000)
        row = {
            "task": task,
            "seed": seed,
            "overrides": OVERRIDES,
            "first_success": next((s.episode for s in history if s.success), None),
            "mean_steps_per_episode": round(sum(s.steps for s in history) / len(history), 1),
            "mean_steps_first_300": round(sum(s.steps for s in history[:300]) / 300, 1),
            "mean_steps_last_100": round(sum(s.steps for s in history[-100:]) / 100, 1),
        }
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
