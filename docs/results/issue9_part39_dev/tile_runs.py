"""Part 39 dev: the tile coder on any task, in ``task_runs.py``'s protocol.

    python tile_runs.py TASK EPISODES OUT SEED [SEED ...]

``TileCodingAgent(space, actions, seed)`` with its defaults, trained for EPISODES episodes from
reset seed = agent seed, then 20 greedy episodes (reset seeds 10^6 + 1,000 seed + i). One JSON
line per seed: the mean training return of each tenth of the run and the mean greedy return.
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np
from protocol import greedy_episodes, tenths  # this folder

from agent import TileCodingAgent, adapt_env


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, episodes, out = argv[1], int(argv[2]), Path(argv[3])
    for seed in map(int, argv[4:]):
        env = adapt_env(gym.make(task))
        agent = TileCodingAgent(env.observation_space, env.action_space, seed)
        history = agent.learn(env, episodes, reset_seed=seed)
        curve = tenths(history, episodes)
        returns, _ = greedy_episodes(env, agent.predict, seed)
        row = {"task": task, "seed": seed, "agent": "tile", "curve": curve}
        row["greedy"] = round(float(np.mean(returns)), 2)
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
