"""Prototype check on Taxi-v4 (integer inputs through ``adapt_env``, the general preset's
table): one training run (600 episodes, the test's protocol), greedy returns from 10 starts
(reset seeds 10,000 + i) under each k of ``supported_greedy.KS``.

    python taxi_support.py OUT SEED [SEED ...]
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

import gymnasium as gym

from agent import adapt_env, general_as_of
from agent.tree_ensemble import tree_agent_class
from supported_greedy import KS, greedy_action

warnings.simplefilter("ignore")
out = Path(sys.argv[1])
for seed in map(int, sys.argv[2:]):
    env = adapt_env(gym.make("Taxi-v4"))
    config = general_as_of(22)
    agent = tree_agent_class(config)(env.observation_space, env.action_space, "adaptive+tabu", seed, config)
    agent.learn(env, 600, reset_seed=seed)
    for k in KS:
        returns = []
        for i in range(10):
            obs, _ = env.reset(seed=10_000 + i)
            total, done = 0.0, False
            while not done:
                obs, r, term, trunc, _ = env.step(greedy_action(agent, obs, k))
                total += float(r)
                done = term or trunc
            returns.append(total)
        with out.open("a") as f:
            f.write(json.dumps({"task": "Taxi-v4", "seed": seed, "k": k, "returns": returns, "delivered": sum(r > 0 for r in returns)}) + "\n")
