"""Part 14 dev probe, mazes: ``local_greedy.py``'s rule on a trained maze agent.

Trains the general preset (committed code) on one development layout, agent seed s, 600
episodes (reset seed 1000 s), then walks 10 greedy episodes (reset seeds 10^6 + 100 s + i,
5,000-step cap) with each ``k`` of ``local_greedy.KS``. The action is chosen where the leaf
changes and kept inside the leaf, as in training (the stored epochs begin at those points);
for ``k = 0`` this is ``predict``'s action. One JSON line per job (steps / optimum)::

    PYTHONPATH=. python docs/results/issue9_part14_dev/local_greedy_maze.py "forest:seed=2" 0
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import preset

sys.path.insert(0, str(Path(__file__).resolve().parent))
from local_greedy import KS, local_action  # beside this file

OUT = Path(__file__).with_name("local_greedy_maze.jsonl")


def walk(agent: Any, env: gym.Env, seed: int, k: int) -> int:
    """Steps of one greedy episode, deciding where the leaf changes."""
    obs, _ = env.reset(seed=seed)
    steps, done, leaf, action = 0, False, -1, 0
    while not done:
        now = agent.leaf_of(obs)
        if now != leaf:
            leaf, action = now, local_action(agent, obs, k)
        obs, _, terminated, truncated, _ = env.step(action)
        steps += 1
        done = terminated or truncated
    return steps


def main(maze: str, seed: int) -> None:
    env = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000)
    optimum = env.unwrapped.optimal_steps  # type: ignore[attr-defined]
    agent = preset("general").agent(env.observation_space, env.action_space, seed)
    start = time.process_time()
    history = agent.learn(env, 600, reset_seed=1000 * seed)
    cpu = time.process_time() - start
    record: dict[str, Any] = {
        "maze": maze,
        "seed": seed,
        "opt": optimum,
        "final": round(float(np.mean([h.steps for h in history[-100:]])) / optimum, 3),
    }
    for k in KS:
        runs = [walk(agent, env, 10**6 + 100 * seed + i, k) for i in range(10)]
        record[f"k{k}"] = round(float(np.mean(runs)) / optimum, 3)
    record.update(leaves=agent.n_leaves, cpu=round(cpu, 1))
    with OUT.open("a") as f:
        f.write(json.dumps(record) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]))
