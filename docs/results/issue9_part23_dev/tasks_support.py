"""Prototype check on the other tasks (integer inputs through ``adapt_env``; the general
preset, ``general_as_of(22)``): one training run (EPISODES), then 100 greedy episodes (reset
seeds 10,000 + i) under k = 0, 1 and 2; the mean greedy return.

    python tasks_support.py OUT TASK EPISODES SEED [SEED ...]
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path
from typing import Any

import gymnasium as gym

from agent import adapt_env, general_as_of, preset
from agent.tree_ensemble import tree_agent_class
from supported_greedy import greedy_returns


def trained(task: str, episodes: int, seed: int, exploration: Any = None) -> tuple[Any, gym.Env]:
    """An agent of part 22's preset after ``episodes`` on ``task`` (first reset seed = seed)."""
    env = adapt_env(gym.make(task))
    config = general_as_of(22)
    strategy = preset("general").make_exploration() if exploration is None else exploration
    agent = tree_agent_class(config)(env.observation_space, env.action_space, strategy, seed, config)
    agent.learn(env, episodes, reset_seed=seed)
    return agent, env


if __name__ == "__main__":
    warnings.simplefilter("ignore")
    out, task, episodes = Path(sys.argv[1]), sys.argv[2], int(sys.argv[3])
    for seed in map(int, sys.argv[4:]):
        agent, env = trained(task, episodes, seed)
        for k in (0, 1, 2):
            returns = greedy_returns(agent, env, k, [10_000 + i for i in range(100)])
            with out.open("a") as f:
                f.write(json.dumps({"task": task, "seed": seed, "k": k, "greedy": sum(returns) / len(returns)}) + "\n")
