"""Part 32, round 2 (a measurement): how often does the general preset settle on a long route on
`paper`, with dev agent seeds? Held out (14103), run 538796146 stayed at 1.53x for 4,000 episodes
(part 32's preset; parts 16-29's: 1.52x). Each row: the training curve's mean steps / optimum
over episodes 250-500, 500-1,000 and the last 100 (of EPISODES), the greedy score (10 episodes),
leaves and the tie trial's state.

    python paper_routes.py OUT EPISODES SEED [SEED ...]
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
    out, episodes = Path(argv[1]), int(argv[2])
    for seed in map(int, argv[3:]):
        env = gym.make("BulletMaze-v0", maze="paper", max_episode_steps=5000)
        agent = preset("general").agent(env.observation_space, env.action_space, seed=seed)
        start = time.process_time()
        history = []
        for b in range(episodes // 50):
            history += agent.learn(env, 50, reset_seed=seed * 1000 + b)
        cpu = time.process_time() - start
        optimum = env.unwrapped.optimal_steps
        steps = np.array([h.steps for h in history], dtype=float) / optimum
        greedy = []
        for i in range(10):
            obs, _ = env.reset(seed=10**6 + i)
            n, done = 0, False
            while not done:
                obs, _, term, trunc, _ = env.step(agent.predict(obs))
                n += 1
                done = term or trunc
            greedy.append(n)
        row = {
            "seed": seed,
            "episodes": episodes,
            "curve_250_500": round(float(steps[250:500].mean()), 3),
            "curve_500_1000": round(float(steps[500:1000].mean()), 3),
            "final": round(float(steps[-100:].mean()), 3),
            "greedy": round(float(np.mean(greedy)) / optimum, 3),
            "leaves": agent.n_leaves,
            "adopted": agent.tie_trial.adopted,
            "cpu": round(cpu, 1),
        }
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
