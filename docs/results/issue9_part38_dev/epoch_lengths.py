"""Part 38 diagnostic: how long are the general preset's epochs?

    python epoch_lengths.py TASK OUT SEED [SEED ...]

TASK is a Gymnasium id (1,000 episodes, its own time limit) or ``maze:SPEC`` for a layout of
``BulletMaze-v0`` (600 episodes, the 5,000-step cap, as the maze suite runs). Trains today's
general preset (reset seed = agent seed) and writes one JSON line per seed: the mean steps per
epoch and per episode in the first, the middle and the last 100 episodes, from the agent's own
per-episode statistics (``EpisodeStats.steps`` and ``.epochs``).
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

import gymnasium as gym

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import adapt_env, preset


def make(task: str) -> tuple[gym.Env, int]:
    if task.startswith("maze:"):
        return gym.make("BulletMaze-v0", maze=task[5:], max_episode_steps=5000), 600
    return adapt_env(gym.make(task)), 1000


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, out = argv[1], Path(argv[2])
    for seed in map(int, argv[3:]):
        env, episodes = make(task)
        agent = preset("general").agent(env.observation_space, env.action_space, seed=seed)
        history = agent.learn(env, episodes, reset_seed=seed)
        row: dict[str, object] = {"task": task, "seed": seed, "leaves": agent.n_leaves}
        for lo in (0, episodes // 2 - 100, episodes - 100):
            block = history[lo : lo + 100]
            steps = sum(s.steps for s in block)
            row[f"steps_per_epoch_{lo}"] = round(steps / sum(s.epochs for s in block), 2)
            row[f"steps_per_episode_{lo}"] = round(steps / len(block), 1)
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
