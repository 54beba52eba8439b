"""Issue 9, part 4: the general preset with and without an option on the classic tasks'
development seeds (agent seeds 0-1, 1,000 episodes, greedy return over 20 episodes).

    python docs/results/issue9_part4/classic_dev.py NAME '{"model_bonus": 0.1}' OUT.jsonl

Each line of OUT.jsonl: name, overrides, task, seed, greedy mean, leaves, CPU seconds. The
greedy episodes reset with seeds 10^6 + 1000 seed + i (tests/agent/test_classic_learning.py).
"""

from __future__ import annotations

import dataclasses
import json
import sys
import time

import gymnasium as gym
import numpy as np

from agent import TreeAgent, preset

TASKS = ("MountainCar-v0", "Acrobot-v1", "CartPole-v1")


def main() -> None:
    name, overrides, out = sys.argv[1], json.loads(sys.argv[2]), sys.argv[3]
    seeds = [int(s) for s in sys.argv[4].split(",")] if len(sys.argv) > 4 else [0, 1]
    general = preset("general")
    config = dataclasses.replace(general.config, **overrides)
    for task in TASKS:
        for seed in seeds:
            env = gym.make(task)
            agent = TreeAgent(
                env.observation_space, env.action_space, general.make_exploration(), seed, config
            )
            start = time.process_time()
            agent.learn(env, 1000, reset_seed=seed)
            returns = []
            for i in range(20):
                obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
                total, done = 0.0, False
                while not done:
                    obs, reward, terminated, truncated, _ = env.step(agent.predict(obs))
                    total += float(reward)
                    done = terminated or truncated
                returns.append(total)
            row = {
                "name": name,
                "overrides": overrides,
                "task": task,
                "seed": seed,
                "greedy": float(np.mean(returns)),
                "leaves": agent.n_leaves,
                "cpu_s": round(time.process_time() - start, 1),
            }
            env.close()
            with open(out, "a") as handle:
                handle.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main()
