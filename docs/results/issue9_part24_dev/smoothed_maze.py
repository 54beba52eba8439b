"""Probe on the dev mazes: the smoothed greedy choice of ``smoothed_greedy.py`` after one
training run of today's preset (``general_as_of(22)``; 600 episodes in blocks of 50, block b
reset with seed 1000 s + b, as part 23's ``maze_support.py``), 10 greedy episodes (reset seeds
10^6 + i) under each h of ``smoothed_greedy.HS``.

    python smoothed_maze.py LAYOUT SEED OUT
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401
from agent import general_as_of, preset
from agent.tree_ensemble import tree_agent_class
from smoothed_greedy import HS, smoothed_action


def main(maze: str, seed: int, out: Path) -> None:
    env = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000)
    probe = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000)
    optimum = env.unwrapped.optimal_steps
    config = general_as_of(22)
    agent = tree_agent_class(config)(env.observation_space, env.action_space, preset("general").make_exploration(), seed, config)
    for block in range(12):
        agent.learn(env, 50, reset_seed=seed * 1000 + block)
    for h in HS:
        runs = []
        for i in range(10):
            obs, _ = probe.reset(seed=10**6 + i)
            n, done = 0, False
            while not done:
                obs, _, term, trunc, _ = probe.step(smoothed_action(agent, obs, h))
                n += 1
                done = term or trunc
            runs.append(n)
        with out.open("a") as f:
            f.write(json.dumps({"maze": maze, "seed": seed, "h": h, "greedy": round(float(np.mean(runs)) / optimum, 3), "capped": sum(r >= 5000 for r in runs)}) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), Path(sys.argv[3]))
