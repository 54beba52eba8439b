"""Part 24's check on float tasks outside the choice (development seeds): one training run of
part 22's preset per seed through ``agent.adapt_env`` (Pendulum's and MountainCarContinuous'
torques as 5 bins), then the 20 greedy episodes of the part 4 protocol under k = 0, 1, 2, 4, 8
(``supported_greedy.py``'s prototype; float inputs never hold a single input, so the preset's
rule there is k = 2 and part 23's k = 1).

    python float_tasks_support.py Pendulum-v1 OUT SEED [SEED ...]
"""

from __future__ import annotations

import json
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "issue9_part23_dev"))
from supported_greedy import KS, episodes  # noqa: E402

from agent import adapt_env, general_as_of, preset  # noqa: E402
from agent.tree_ensemble import tree_agent_class  # noqa: E402

def train(task: str, seed: int):
    """One training run of part 22's preset (part 24's training) through ``agent.adapt_env``:
    1,000 episodes, first reset seed = agent seed. Returns (env, agent, CPU seconds)."""
    env = adapt_env(gym.make(task))
    config = general_as_of(22)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, preset("general").make_exploration(), seed, config
    )
    start = time.process_time()
    agent.learn(env, 1000, reset_seed=seed)
    return env, agent, time.process_time() - start


if __name__ == "__main__":
    warnings.simplefilter("ignore")
    task, out = sys.argv[1], Path(sys.argv[2])
    for seed in map(int, sys.argv[3:]):
        env, agent, cpu = train(task, seed)
        for k in KS:
            returns = episodes(agent, env, seed, k)
            with out.open("a") as f:
                f.write(json.dumps({"task": task, "seed": seed, "k": k, "greedy": round(float(np.mean(returns)), 2), "leaves": agent.n_leaves, "cpu": round(cpu, 1)}) + "\n")
