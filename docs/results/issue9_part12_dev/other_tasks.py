"""The general preset, unchanged, on Gymnasium tasks it was never tuned or developed on
(issue 9, part 12): each through ``agent.adapt_env`` (an index input for a Discrete or Tuple
observation; 5 values per dimension for a Box action). Agent seeds 0-2, first reset seed s,
1,000 episodes, then 100 greedy episodes (reset seeds 10^6 + 1000 s + i) and 100 episodes of
a uniformly random policy on the same resets (its generator seeded with s). One JSON line per
run::

    PYTHONPATH=. python docs/results/issue9_part12_dev/other_tasks.py OUT.jsonl TASK SEED
"""

from __future__ import annotations

import json
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

from agent import adapt_env, preset


def episode_return(env: gym.Env, seed: int, act) -> float:
    obs, _ = env.reset(seed=seed)
    total, done = 0.0, False
    while not done:
        obs, reward, terminated, truncated, _ = env.step(act(obs))
        total += float(reward)
        done = terminated or truncated
    return total


def main(out: str, task: str, seed: int) -> None:
    warnings.simplefilter("ignore")
    env = adapt_env(gym.make(task))
    agent = preset("general").agent(env.observation_space, env.action_space, seed=seed)
    start = time.process_time()
    history = agent.learn(env, 1000, reset_seed=seed)
    cpu = time.process_time() - start
    greedy = [episode_return(env, 10**6 + 1000 * seed + i, agent.predict) for i in range(100)]
    rng = np.random.default_rng(seed)
    n = int(env.action_space.n)  # type: ignore[attr-defined]
    random = [
        episode_return(env, 10**6 + 1000 * seed + i, lambda _: int(rng.integers(n)))
        for i in range(100)
    ]
    spec = gym.spec(task)
    record = {
        "task": task,
        "seed": seed,
        "observation": str(env.observation_space),
        "actions": n,
        "greedy": round(float(np.mean(greedy)), 3),
        "random": round(float(np.mean(random)), 3),
        "solved": spec.reward_threshold,
        "train_last100": round(float(np.mean([h.episode_return for h in history[-100:]])), 3),
        "leaves": agent.n_leaves,
        "cpu": round(cpu, 1),
    }
    with Path(out).open("a") as f:
        f.write(json.dumps(record) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))
