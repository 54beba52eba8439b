"""Part 41 dev: the tile coder with some parameters changed, in part 39's protocol.

    PARAMS='{"epsilon": 0.1}' python tile_params.py TASK EPISODES OUT SEED [SEED ...]

``TileCodingAgent(space, actions, seed, **PARAMS)``, trained for EPISODES episodes from reset
seed = agent seed, then 20 greedy episodes (reset seeds 10^6 + 1,000 seed + i; part 39's
``protocol.py``). One JSON line per seed: the parameters, the mean training return of each
tenth of the run, the mean greedy return and the CPU seconds of training.
"""

from __future__ import annotations

import json
import os
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "issue9_part39_dev"))
from protocol import greedy_episodes, tenths

from agent import TileCodingAgent, adapt_env

PARAMS = json.loads(os.environ.get("PARAMS", "{}"))


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, episodes, out = argv[1], int(argv[2]), Path(argv[3])
    for seed in map(int, argv[4:]):
        env = adapt_env(gym.make(task))
        agent = TileCodingAgent(env.observation_space, env.action_space, seed, **PARAMS)
        start = time.process_time()
        history = agent.learn(env, episodes, reset_seed=seed)
        cpu = time.process_time() - start
        returns, _ = greedy_episodes(env, agent.predict, seed)
        row = {
            "task": task,
            "seed": seed,
            "params": PARAMS,
            "curve": tenths(history, episodes),
            "greedy": round(float(np.mean(returns)), 2),
            "cpu": round(cpu, 1),
        }
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
