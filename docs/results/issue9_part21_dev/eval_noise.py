"""Issue 9, part 21 (development): how much of a classic row ("8 of 10 at -110" on
MountainCar, "at 475" on CartPole) is the evaluation's sampling. Trains today's preset as part 4's classic driver does (agent and
first reset seed s, 1,000 episodes), scores the 20 greedy episodes of the dev protocol
(resets 10^6 + 1000 s + i) and 200 more (resets 2 x 10^6 + 1000 s + i), and appends one JSON
line to ``eval_noise.jsonl``::

    python docs/results/issue9_part21_dev/eval_noise.py SEED [TASK]   # TASK: MountainCar-v0
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np

from agent import preset


def greedy(agent: object, env: gym.Env, seeds: range) -> list[float]:
    out = []
    for seed in seeds:
        obs, _ = env.reset(seed=seed)
        total, done = 0.0, False
        while not done:
            obs, reward, terminated, truncated, _ = env.step(agent.predict(obs))  # type: ignore[attr-defined]
            total += float(reward)
            done = terminated or truncated
        out.append(total)
    return out


if __name__ == "__main__":
    seed = int(sys.argv[1])
    task = sys.argv[2] if len(sys.argv) > 2 else "MountainCar-v0"
    general = preset("general")
    env = gym.make(task)
    agent = general.agent(env.observation_space, env.action_space, seed=seed)
    agent.learn(env, 1000, reset_seed=seed)
    twenty = greedy(agent, env, range(1_000_000 + 1000 * seed, 1_000_000 + 1000 * seed + 20))
    more = greedy(agent, env, range(2_000_000 + 1000 * seed, 2_000_000 + 1000 * seed + 200))
    line = {
        **({} if task == "MountainCar-v0" else {"task": task}),
        "seed": seed,
        "greedy20": round(float(np.mean(twenty)), 2),
        "greedy200": round(float(np.mean(more)), 2),
        "sd": round(float(np.std(more, ddof=1)), 2),
    }
    with Path(__file__).with_name("eval_noise.jsonl").open("a") as f:
        f.write(json.dumps(line) + "\n")
