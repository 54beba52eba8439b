"""Part 33 dev diagnostic: are Acrobot's misses made by a few long greedy episodes, and are
those episodes loops?

The general preset (part 32's) on ``Acrobot-v1`` (dev agent seeds), 1,000 training episodes
from reset seed ``seed`` (part 30's protocol), then 20 greedy episodes from reset seeds
1,000,000 + 1,000 seed + i. For each run: the mean return, the mean without episodes longer
than 200 steps, and for each long episode the period of its leaf sequence over its last 100
steps (the least p <= 50 with leaf[t] == leaf[t - p] for all of them, else None) and how far
its state is from the state p steps before (the largest absolute difference of the six
inputs)::

    python acrobot_tails.py OUT SEED [SEED ...]
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

from agent import adapt_env, preset


def period(leaves: list[int]) -> int | None:
    tail = leaves[-100:]
    for p in range(1, 51):
        if all(tail[t] == tail[t - p] for t in range(p, len(tail))):
            return p
    return None


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    out = Path(argv[1])
    for seed in map(int, argv[2:]):
        env = adapt_env(gym.make("Acrobot-v1"))
        agent = preset("general").agent(env.observation_space, env.action_space, seed)
        agent.learn(env, 1000, reset_seed=seed)
        episodes = []
        for i in range(20):
            obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
            states, leaves, total, done = [np.asarray(obs, float)], [agent.leaf_of(obs)], 0.0, False
            while not done:
                obs, reward, term, trunc, _ = env.step(agent.predict(obs))
                total += float(reward)
                done = term or trunc
                states.append(np.asarray(obs, float))
                leaves.append(agent.leaf_of(obs))
            row = {"i": i, "return": total, "steps": len(states) - 1}
            if len(states) > 201:
                p = period(leaves)
                row["period"] = p
                if p is not None:
                    row["state_gap"] = round(float(np.abs(states[-1] - states[-1 - p]).max()), 4)
            episodes.append(row)
        returns = [e["return"] for e in episodes]
        short = [e["return"] for e in episodes if e["steps"] <= 200]
        rec = {
            "seed": seed,
            "mean": round(float(np.mean(returns)), 2),
            "mean_short": round(float(np.mean(short)), 2) if short else None,
            "long": [e for e in episodes if e["steps"] > 200],
            "leaves": agent.n_leaves,
        }
        with out.open("a") as f:
            f.write(json.dumps(rec) + "\n")


if __name__ == "__main__":
    main(sys.argv)
