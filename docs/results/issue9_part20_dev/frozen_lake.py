"""Issue 9, part 20 (development): FrozenLake (slippery, 4x4 or 8x8) under the general preset of
a given part with TreeConfig overrides; 1,000 episodes, then the greedy policy from 200 starts
(reset seeds 10,000 + i, as tests/agent/test_optimism.py). One JSON line per run::

    python docs/results/issue9_part20_dev/frozen_lake.py TASK PART SEED LABEL OVERRIDES_JSON OUT
"""

from __future__ import annotations

import dataclasses
import json
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym

from agent import adapt_env, general_as_of, preset
from agent.tree_ensemble import tree_agent_class


def main(task: str, part: int, seed: int, label: str, overrides: dict, out: str) -> None:
    warnings.simplefilter("ignore")
    env = adapt_env(gym.make(task))
    config = dataclasses.replace(general_as_of(part), **overrides)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, preset("general").make_exploration(), seed,
        config,
    )
    start = time.process_time()
    agent.learn(env, 1000, reset_seed=seed)
    wins = 0
    for i in range(200):
        obs, _ = env.reset(seed=10_000 + i)
        done, reward = False, 0.0
        while not done:
            obs, reward, terminated, truncated, _ = env.step(agent.predict(obs))
            done = terminated or truncated
        wins += reward > 0
    line = {
        "task": task, "part": part, "label": label, "overrides": overrides, "seed": seed,
        "success": wins / 200, "latched": bool(getattr(agent, "failure_discount", False)),
        "leaves": agent.n_leaves, "cpu": round(time.process_time() - start, 1),
    }
    with Path(out).open("a") as f:
        f.write(json.dumps(line) + "\n")


if __name__ == "__main__":
    a = sys.argv[1:]
    main(a[0], int(a[1]), int(a[2]), a[3], json.loads(a[4]), a[5])
