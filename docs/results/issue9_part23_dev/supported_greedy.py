"""Prototype of a greedy choice among *supported* actions: in the leaf that holds the state,
only the actions with at least k stored epochs in the leaf's model compete (all of them when
none has k). Training is untouched (the prototype only changes ``predict``), so one training
run per seed is evaluated under every k (k = 0 is today's greedy choice).

    python supported_greedy.py TASK OUT SEED [SEED ...]
    OVERRIDES='{"policy_splits": true}' python supported_greedy.py ...   (TreeConfig fields)

One JSON line per (seed, k): the 20 greedy episodes of the part 4 protocol (reset seeds
10^6 + 1000 seed + i) and their mean; training is today's preset (``general_as_of(22)``),
1,000 episodes, first reset seed = agent seed.
"""

from __future__ import annotations

import dataclasses
import json
import os
import sys
import time
from pathlib import Path

import gymnasium as gym
import numpy as np

from agent import general_as_of, preset
from agent.tree_ensemble import tree_agent_class

KS = (0, 1, 2, 4, 8)


def greedy_action(agent, obs, k: int) -> int:
    x = np.asarray(obs, dtype=np.float64).reshape(-1).tolist()
    leaf = agent.partition.leaf_of(x)
    row = agent.q[leaf]
    actions = range(agent.n_actions)
    if k > 0:
        allowed = [a for a in actions if agent.model.count(leaf, a) >= k]
        if allowed:
            actions = allowed
    return max(actions, key=row.__getitem__)


def greedy_returns(agent, env, k: int, reset_seeds, choose=None) -> list[float]:
    """Returns of greedy episodes under k (or ``choose(obs)``), one reset with each seed."""
    if choose is None:
        choose = lambda obs: greedy_action(agent, obs, k)  # noqa: E731
    out = []
    for reset_seed in reset_seeds:
        obs, _ = env.reset(seed=reset_seed)
        total, done = 0.0, False
        while not done:
            obs, reward, terminated, truncated, _ = env.step(choose(obs))
            total += float(reward)
            done = terminated or truncated
        out.append(total)
    return out


def episodes(agent, env, seed: int, k: int) -> list[float]:
    """The 20 greedy episodes of the part 4 protocol."""
    return greedy_returns(agent, env, k, [1_000_000 + 1000 * seed + i for i in range(20)])


def main(task: str, out: Path, seeds: list[int]) -> None:
    for seed in seeds:
        env = gym.make(task)
        general = preset("general")
        overrides = json.loads(os.environ.get("OVERRIDES", "{}"))
        config = dataclasses.replace(general_as_of(22), **overrides)
        agent = tree_agent_class(config)(env.observation_space, env.action_space, general.make_exploration(), seed, config)
        start = time.process_time()
        agent.learn(env, 1000, reset_seed=seed)
        cpu = time.process_time() - start
        for k in KS:
            returns = episodes(agent, env, seed, k)
            with out.open("a") as f:
                f.write(json.dumps({"task": task, "seed": seed, "k": k, "overrides": overrides, "greedy": round(float(np.mean(returns)), 2),
                                    "greedy_all": [round(r) for r in returns], "leaves": agent.n_leaves, "cpu": round(cpu, 1)}) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], Path(sys.argv[2]), [int(s) for s in sys.argv[3:]])
