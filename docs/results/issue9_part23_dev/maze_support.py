"""Prototype check on the dev mazes: one training run of today's preset (``general_as_of(22)``;
600 episodes in blocks of 50, block b reset with seed 1000 s + b, as part 8's ``curves.py``),
then 10 greedy episodes (reset seeds 10^6 + i) under each k of ``supported_greedy.KS``.

    python maze_support.py LAYOUT SEED OUT

One JSON line per (layout, seed, k): greedy steps / optimum (mean over the 10), how many hit the
5,000-step cap, and the training AUC and final (to check the run is the recorded one).
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
from supported_greedy import KS, greedy_action


def main(maze: str, seed: int, out: Path) -> None:
    env = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000)
    probe = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000)
    optimum = env.unwrapped.optimal_steps
    general = preset("general")
    config = general_as_of(22)
    agent = tree_agent_class(config)(env.observation_space, env.action_space, general.make_exploration(), seed, config)
    train = []
    for block in range(12):
        train += [h.steps for h in agent.learn(env, 50, reset_seed=seed * 1000 + block)]
    steps = np.array(train, dtype=float)
    for k in KS:
        runs = []
        for i in range(10):
            obs, _ = probe.reset(seed=10**6 + i)
            n, done = 0, False
            while not done:
                obs, _, term, trunc, _ = probe.step(greedy_action(agent, obs, k))
                n += 1
                done = term or trunc
            runs.append(n)
        with out.open("a") as f:
            f.write(json.dumps({"maze": maze, "seed": seed, "k": k, "greedy": round(float(np.mean(runs)) / optimum, 3),
                                "capped": sum(r >= 5000 for r in runs), "auc": round(float(steps.mean()) / optimum, 3),
                                "final": round(float(steps[-100:].mean()) / optimum, 3)}) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), Path(sys.argv[3]))
