"""Part 38: when does today's general preset first reach the goal?

    OVERRIDES='{"novelty_cells": 4}' python first_success.py TASK EPISODES SEED [SEED ...]

Prints one JSON line per seed: the first episode that reached the goal and the mean steps per
episode in blocks of 25 (reset seed = agent seed). The lines of today's preset in
``first_success.jsonl`` came from the same script without ``OVERRIDES``.
"""

from __future__ import annotations

import dataclasses
import json
import os
import sys
import warnings

import gymnasium as gym

from agent import EpisodeStats, adapt_env, preset
from agent.tree_ensemble import tree_agent_class

OVERRIDES = json.loads(os.environ.get("OVERRIDES", "{}"))


def train(task: str, seed: int, episodes: int) -> list[EpisodeStats]:
    """Today's general preset with ``OVERRIDES``, trained from reset seed = agent seed."""
    general = preset("general")
    config = dataclasses.replace(general.config, **OVERRIDES)
    env = adapt_env(gym.make(task))
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, general.make_exploration(), seed, config
    )
    return agent.learn(env, episodes, reset_seed=seed)


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, episodes = argv[1], int(argv[2])
    for seed in map(int, argv[3:]):
        history = train(task, seed, episodes)
        blocks = [
            round(sum(s.steps for s in history[i : i + 25]) / 25) for i in range(0, episodes, 25)
        ]
        first = next((s.episode for s in history if s.success), None)
        row = {"task": task, "seed": seed, "ov": OVERRIDES, "first_success": first}
        sys.stdout.write(json.dumps({**row, "steps_per_25": blocks}) + "\n")


if __name__ == "__main__":
    main(sys.argv)
