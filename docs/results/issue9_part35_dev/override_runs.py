"""Part 34 dev probe (round 5; reused in part 35): today's general preset with TreeConfig fields overridden.

    OVERRIDES='{"sweep_backups": 256}' python override_runs.py TASK OUT SEED [SEED ...]

Part 30's classic protocol (1,000 episodes from reset seed = agent seed; 20 greedy episodes from
reset seeds 10^6 + 1,000 seed + i); one JSON line per seed with the mean greedy return, the
greedy episodes past 200 steps, the leaves and the CPU seconds of training.
"""

from __future__ import annotations

import dataclasses
import json
import os
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

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
        start = time.process_time()
        agent.learn(env, 1000, reset_seed=seed)
        row = {"task": task, "seed": seed, "overrides": OVERRIDES}
        row["cpu"] = round(time.process_time() - start, 1)
        row["leaves"] = agent.n_leaves
        returns = []
        for i in range(20):
            obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
            total, done = 0.0, False
            while not done:
                obs, reward, term, trunc, _ = env.step(agent.predict(obs))
                total += float(reward)
                done = term or trunc
            returns.append(total)
        row["mean"] = round(float(np.mean(returns)), 2)
        row["long"] = sum(r <= -200 for r in returns)
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
