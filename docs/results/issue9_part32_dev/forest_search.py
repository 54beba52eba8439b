"""Part 32, round 3 (a measurement): dev forests whose learnt route is far above what a compass
mover needs. For each layout, the general preset (part 32's) with one agent seed, 600
episodes in blocks of 50 (reset seeds seed * 1000 + block), then 10 greedy episodes; the row
keeps the training final and the greedy score over the optimum, and the lattice bound (the
least compass steps on the lattice of the start's positions, ``PhysicalLimit.lattice_steps``)
over the optimum.

    python forest_search.py OUT AGENT_SEED LAYOUT [LAYOUT ...]
"""

from __future__ import annotations

import json
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401  (registers the maze)
from agent import preset


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    out, seed = Path(argv[1]), int(argv[2])
    for layout in argv[3:]:
        env = gym.make("BulletMaze-v0", maze=layout, max_episode_steps=5000)
        agent = preset("general").agent(env.observation_space, env.action_space, seed=seed)
        start = time.process_time()
        history = []
        for b in range(12):
            history += agent.learn(env, 50, reset_seed=seed * 1000 + b)
        cpu = time.process_time() - start
        limit = env.unwrapped.physical_limit
        optimum = limit.steps
        greedy = []
        for i in range(10):
            obs, _ = env.reset(seed=10**6 + i)
            n, done = 0, False
            while not done:
                obs, _, term, trunc, _ = env.step(agent.predict(obs))
                n += 1
                done = term or trunc
            greedy.append(n)
        steps = np.array([h.steps for h in history], dtype=float)
        row = {
            "layout": layout,
            "seed": seed,
            "optimum": optimum,
            "lattice": round(limit.lattice_steps / optimum, 3),
            "final": round(float(steps[-100:].mean()) / optimum, 3),
            "greedy": round(float(np.mean(greedy)) / optimum, 3),
            "leaves": agent.n_leaves,
            "cpu": round(cpu, 1),
        }
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
