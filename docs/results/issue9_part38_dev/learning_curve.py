"""Part 38, round 2: the learning curve of today's general preset, with TreeConfig overrides.

    OVERRIDES='{"novelty_cells": 4}' python learning_curve.py TASK OUT SEED [SEED ...]

1,000 episodes from reset seed = agent seed; one JSON line per seed with the first episode that
reached the goal and the mean steps per episode over the run, its first 300 and its last 100.
"""

from __future__ import annotations

import dataclasses
import json
import os
import sys
import warnings
from pathlib import Path

import gymnasium as gym

from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class

OVERRIDES = json.loads(os.environ.get("OVERRIDES", "{}"))


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, out = argv[1], Path(argv[2])
    general = preset("general")
    config = dataclasses.replace(general.config, **OVERRIDES)
    for seed in map(int, argv[3:]):
        env = adapt_env(gym.make(task))
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, general.make_exploration(), seed, config
        )
        history = agent.learn(env, 1000, reset_seed=seed)
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
