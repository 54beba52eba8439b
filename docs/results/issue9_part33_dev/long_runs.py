"""Part 33 dev diagnostic: does a settled forest route move with more episodes? The general
preset (``CUT=1``: with ``collision_splits_collided_only``), one agent seed, 1,500 episodes
in blocks of 50 (reset seeds seed * 1000 + block, so the first 600 are those of
``forest_search.py``); every 300 episodes the greedy score over 10 episodes (reset seeds
10^6 + i), the training mean of the last 100 over the optimum, and the leaves::

    CUT=0|1 python long_runs.py OUT AGENT_SEED LAYOUT [LAYOUT ...]
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401  (registers the maze)

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cut_runs import general  # noqa: E402


def greedy(env, agent) -> float:
    scores = []
    for i in range(10):
        obs, _ = env.reset(seed=10**6 + i)
        n, done = 0, False
        while not done:
            obs, _, term, trunc, _ = env.step(agent.predict(obs))
            n, done = n + 1, term or trunc
        scores.append(n)
    return float(np.mean(scores))


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    out, seed = Path(argv[1]), int(argv[2])
    for layout in argv[3:]:
        env = gym.make("BulletMaze-v0", maze=layout, max_episode_steps=5000)
        agent = general().agent(env.observation_space, env.action_space, seed)
        optimum = env.unwrapped.optimal_steps
        history, marks = [], []
        for b in range(30):
            history += agent.learn(env, 50, reset_seed=seed * 1000 + b)
            if (b + 1) % 6 == 0:
                steps = np.array([h.steps for h in history[-100:]], dtype=float)
                marks.append(
                    (len(history), round(greedy(env, agent) / optimum, 3),
                     round(float(steps.mean()) / optimum, 3), agent.n_leaves)
                )
        with out.open("a") as f:
            f.write(json.dumps({"layout": layout, "seed": seed, "marks": marks}) + "\n")


if __name__ == "__main__":
    main(sys.argv)
