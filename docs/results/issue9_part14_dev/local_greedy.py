"""Part 14 dev probe: does a leaf's own evidence rank the actions better near the state?

Q-bar(leaf, a) averages the eq. (8) targets of every stored epoch of (leaf, a), wherever in the
leaf it began. This probe trains the general preset (committed code; 1,000 episodes on a
classic task, first reset seed = agent seed), then scores 20 greedy episodes (reset seeds
10^6 + 1000 s + i) with ``predict`` (``k = 0``) and with a local rule: at state x, each
action's value is the mean eq. (8) target of the ``k`` stored epochs of (leaf, a) whose first
inputs lie nearest x (distance in units of the leaf's widths), Q-bar where the action has fewer
than ``k`` epochs. One JSON line per job::

    PYTHONPATH=. python docs/results/issue9_part14_dev/local_greedy.py TASK SEED
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from agent import preset

OUT = Path(__file__).with_name("local_greedy.jsonl")
KS = (0, 1, 3, 5, 9)


def local_action(agent: Any, obs: Any, k: int) -> int:
    """The greedy action by the ``k`` nearest stored epochs of each action (0: ``predict``)."""
    if k == 0:
        return int(agent.predict(obs))
    x = np.asarray(obs, dtype=float).reshape(-1)
    leaf = agent.leaf_of(obs)
    low, high = (np.asarray(b, dtype=float) for b in agent.partition.leaf_bounds(leaf))
    width = np.where(high > low, high - low, 1.0)
    values = list(agent.q[leaf])
    for a in range(agent.n_actions):
        firsts, targets = agent.model.targets(leaf, a, agent.q)
        if len(targets) < k:
            continue
        d = np.abs((np.asarray(firsts, dtype=float) - x) / width).max(axis=1)
        nearest = np.argsort(d, kind="stable")[:k]
        values[a] = float(np.mean(np.asarray(targets)[nearest]))
    return int(np.argmax(values))


def greedy(agent: Any, env: gym.Env, seeds: list[int], k: int) -> float:
    """Mean return of greedy episodes from the given reset seeds."""
    returns = []
    for seed in seeds:
        obs, _ = env.reset(seed=seed)
        total, done = 0.0, False
        while not done:
            obs, reward, terminated, truncated, _ = env.step(local_action(agent, obs, k))
            total += float(reward)
            done = terminated or truncated
        returns.append(total)
    return float(np.mean(returns))


def main(task: str, seed: int) -> None:
    env = gym.make(task)
    agent = preset("general").agent(env.observation_space, env.action_space, seed)
    start = time.process_time()
    agent.learn(env, 1000, reset_seed=seed)
    cpu = time.process_time() - start
    seeds = [1_000_000 + 1000 * seed + i for i in range(20)]
    record: dict[str, Any] = {"task": task, "seed": seed}
    for k in KS:
        record[f"k{k}"] = round(greedy(agent, env, seeds, k), 1)
    record.update(leaves=agent.n_leaves, cpu=round(cpu, 1))
    with OUT.open("a") as f:
        f.write(json.dumps(record) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]))
