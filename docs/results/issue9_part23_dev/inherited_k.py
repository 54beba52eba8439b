"""Probe: a stricter count only where a leaf's row was handed down by a learned split. Leaves
that exist before the first episode (the presplit, a table's cells) need one stored epoch of
an action, leaves made by a split during learning need two (``greedy_action_inherited``).

    python inherited_k.py MountainCar-v0 OUT SEED [SEED ...]   (20 greedy episodes, as part 4)
    python inherited_k.py Taxi-v4 OUT SEED [SEED ...]          (600 episodes, 10 starts, as the table test)
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

from agent import adapt_env, general_as_of, preset
from agent.tree_ensemble import tree_agent_class
from supported_greedy import greedy_returns


def greedy_action_inherited(agent, obs, first_learned: int) -> int:
    x = np.asarray(obs, dtype=np.float64).reshape(-1).tolist()
    leaf = agent.partition.leaf_of(x)
    row = agent.q[leaf]
    k = 2 if leaf >= first_learned else 1
    allowed = [a for a in range(agent.n_actions) if agent.model.count(leaf, a) >= k]
    return max(allowed or range(agent.n_actions), key=row.__getitem__)


if __name__ == "__main__":
    warnings.simplefilter("ignore")
    task, out = sys.argv[1], Path(sys.argv[2])
    taxi = task == "Taxi-v4"
    for seed in map(int, sys.argv[3:]):
        env = adapt_env(gym.make(task))
        config = general_as_of(22)
        strategy = "adaptive+tabu" if taxi else preset("general").make_exploration()
        agent = tree_agent_class(config)(env.observation_space, env.action_space, strategy, seed, config)
        first_learned = agent.partition.n_ids  # ids from here on are made while learning
        agent.learn(env, 600 if taxi else 1000, reset_seed=seed)
        starts = [10_000 + i for i in range(10)] if taxi else [1_000_000 + 1000 * seed + i for i in range(20)]
        returns = greedy_returns(agent, env, 0, starts, lambda obs: greedy_action_inherited(agent, obs, first_learned))
        with out.open("a") as f:
            f.write(json.dumps({"task": task, "seed": seed, "rule": "k2-inherited", "greedy": float(np.mean(returns)), "returns": [round(r) for r in returns], "first_learned": first_learned}) + "\n")
