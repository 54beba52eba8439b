"""Issue 9, part 16 (development): the general preset of part 15 (``general_as_of(15)``, the
preset the runs started from) with TreeConfig overrides on a task
through ``agent.adapt_env``: 1,000 episodes from first reset seed SEED, then 100 greedy
episodes (reset seeds 10^6 + 1000 SEED + i). One JSON line per run::

    python docs/results/issue9_part16_dev/tasks_dev.py OUT.jsonl TASK SEED LABEL '{"optimistic_untried": true}'
"""

from __future__ import annotations

import dataclasses
import json
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

from agent import adapt_env, general_as_of
from agent.tree_ensemble import tree_agent_class


def episode_return(env: gym.Env, seed: int, act) -> float:
    obs, _ = env.reset(seed=seed)
    total, done = 0.0, False
    while not done:
        obs, reward, terminated, truncated, _ = env.step(act(obs))
        total += float(reward)
        done = terminated or truncated
    return total


def main(out: str, task: str, seed: int, label: str, overrides: str) -> None:
    warnings.simplefilter("ignore")
    config = dataclasses.replace(general_as_of(15), **json.loads(overrides))
    env = adapt_env(gym.make(task))
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "adaptive+tabu", seed, config
    )
    start = time.process_time()
    history = agent.learn(env, 1000, reset_seed=seed)
    cpu = time.process_time() - start
    greedy = [episode_return(env, 10**6 + 1000 * seed + i, agent.predict) for i in range(100)]
    blocks = [
        round(float(np.mean([h.episode_return for h in history[i : i + 100]])), 3)
        for i in range(0, 1000, 100)
    ]
    record = {
        "task": task,
        "seed": seed,
        "label": label,
        "overrides": json.loads(overrides),
        "greedy": round(float(np.mean(greedy)), 3),
        "train_blocks": blocks,
        "leaves": agent.n_leaves,
        "cpu": round(cpu, 1),
    }
    with Path(out).open("a") as f:
        f.write(json.dumps(record) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5])
