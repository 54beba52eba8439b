"""Issue 9, part 15 (development): the general preset with the table for integer inputs
(``table``) and part 14's preset without it (``before``), on a task through ``agent.adapt_env``:
1,000 episodes from first reset seed SEED, then 100 greedy episodes (reset seeds
10^6 + 1000 SEED + i). One JSON line per run::

    python docs/results/issue9_part15_dev/table_dev.py OUT.jsonl TASK SEED table|before
"""

import json
import sys
import time
import warnings

import gymnasium as gym
import numpy as np

from agent import adapt_env, general_as_of
from agent.tree_ensemble import tree_agent_class


def episode_return(env, seed, act):
    obs, _ = env.reset(seed=seed)
    total, done = 0.0, False
    while not done:
        obs, reward, terminated, truncated, _ = env.step(act(obs))
        total += float(reward)
        done = terminated or truncated
    return total


def main(out, task, seed, arm):
    warnings.simplefilter("ignore")
    config = general_as_of(15) if arm == "table" else general_as_of(14)  # the runs' presets
    env = adapt_env(gym.make(task))
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "adaptive+tabu", seed, config
    )
    start = time.process_time()
    history = agent.learn(env, 1000, reset_seed=seed)
    cpu = time.process_time() - start
    greedy = [episode_return(env, 10**6 + 1000 * seed + i, agent.predict) for i in range(100)]
    curve = [
        round(float(np.mean([h.episode_return for h in history[i : i + 100]])), 2)
        for i in range(0, 1000, 100)
    ]
    record = {
        "task": task,
        "seed": seed,
        "arm": arm,
        "greedy": round(float(np.mean(greedy)), 3),
        "curve": curve,
        "leaves": agent.n_leaves,
        "cpu": round(cpu, 1),
    }
    with open(out, "a") as f:
        f.write(json.dumps(record) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4])
