"""Part 13 dev probe: what the general preset's late training episodes spend on exploration.

One dev layout, agent seed s, 600 episodes (reset seed s); prints, per block of 100 episodes,
the mean steps / optimum, the mean exploration rate at the decision points (EpisodeStats.
mean_epsilon), and 5 greedy episodes' steps / optimum after training (reset seeds 10^6 + i).
One JSON line per job to ``late_exploration.jsonl``::

    PYTHONPATH=. python docs/results/issue9_part13_dev/late_exploration.py "forest:seed=2" 0
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import preset

OUT = Path(__file__).with_name("late_exploration.jsonl")


def main(maze: str, seed: int) -> None:
    env = gym.make("BulletMaze-v0", maze=maze, max_episode_steps=5000)
    optimum = env.unwrapped.optimal_steps  # type: ignore[attr-defined]
    agent = preset("general").agent(env.observation_space, env.action_space, seed)
    history = agent.learn(env, 600, reset_seed=seed)
    blocks = [history[b : b + 100] for b in range(0, 600, 100)]
    greedy = []
    for i in range(5):
        obs, _ = env.reset(seed=10**6 + i)
        steps, done = 0, False
        while not done:
            obs, _, terminated, truncated, _ = env.step(agent.predict(obs))
            steps += 1
            done = terminated or truncated
        greedy.append(round(steps / optimum, 2))
    record = {
        "maze": maze,
        "seed": seed,
        "steps": [round(float(np.mean([h.steps for h in b])) / optimum, 2) for b in blocks],
        "epsilon": [round(float(np.mean([h.mean_epsilon for h in b])), 4) for b in blocks],
        "collisions": [round(float(np.mean([h.collisions for h in b])), 2) for b in blocks],
        "greedy": greedy,
        "leaves": agent.n_leaves,
    }
    with OUT.open("a") as f:
        f.write(json.dumps(record) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]))
