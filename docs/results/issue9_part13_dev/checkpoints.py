"""Part 13 dev probe: is the general agent's last policy its best one?

Trains the general preset on one classic task and dev seed for 1,000 episodes in blocks of
50 (the first reset seeded with the agent seed, the env's own generator after it, so the run
is the one ``learn(env, 1000, reset_seed=seed)`` makes), keeps the agent after every block,
then scores each kept agent's greedy policy over 20 episodes (reset seeds 10^6 + 1000 s + i,
the protocol of tests/agent/test_classic_learning.py). One JSON line per job to
``checkpoints.jsonl``: the training return of each block and the greedy return after it::

    PYTHONPATH=. python docs/results/issue9_part13_dev/checkpoints.py CartPole-v1 0
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

import gymnasium as gym
import numpy as np

from agent import preset
from agent.tree_ensemble import tree_agent_class

OUT = Path(__file__).with_name("checkpoints.jsonl")
BLOCK = 50


def greedy(agent: object, env: gym.Env, seed: int) -> float:
    returns = []
    for i in range(20):
        obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
        total, done = 0.0, False
        while not done:
            obs, reward, terminated, truncated, _ = env.step(agent.predict(obs))  # type: ignore[attr-defined]
            total += float(reward)
            done = terminated or truncated
        returns.append(total)
    return float(np.mean(returns))


def main(task: str, seed: int) -> None:
    general = preset("general")
    env, probe = gym.make(task), gym.make(task)
    agent = general.agent(env.observation_space, env.action_space, seed)
    train, scores = [], []
    with tempfile.TemporaryDirectory() as folder:
        for block in range(1000 // BLOCK):
            history = agent.learn(env, BLOCK, reset_seed=seed if block == 0 else None)
            train.append(round(float(np.mean([h.episode_return for h in history])), 1))
            path = agent.save(Path(folder) / f"b{block}.npz")
            kept = tree_agent_class(general.config).load(path)
            scores.append(round(greedy(kept, probe, seed), 1))
    record = {"task": task, "seed": seed, "train": train, "greedy": scores}
    with OUT.open("a") as f:
        f.write(json.dumps(record) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]))
