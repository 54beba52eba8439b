"""Part 13 dev probe: is the general agent's greedy policy the one it learnt?

Trains the general preset (committed code) on one classic task and dev seed (1,000 episodes,
first reset seed = agent seed), saves the agent, then scores 20 greedy episodes (reset seeds
10^6 + 1000 s + i, the protocol of tests/agent/test_classic_learning.py) two ways:

* ``step``: ``predict`` at every step (the harness's evaluation);
* ``held``: the greedy action kept until the leaf changes or ``max_epoch_steps`` steps, the
  decision points of training (an SMDP option per leaf, eqs. 9-10).

One JSON line per job to ``held_greedy.jsonl``::

    PYTHONPATH=. python docs/results/issue9_part13_dev/held_greedy.py TASK SEED [SAVE_DIR]
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from agent import preset

OUT = Path(__file__).with_name("held_greedy.jsonl")


def episode(agent: Any, env: gym.Env, seed: int, held: bool) -> float:
    """The return of one greedy episode; ``held`` keeps an action to the leaf's edge."""
    obs, _ = env.reset(seed=seed)
    cap = agent.config.max_epoch_steps or 10**9
    total, done = 0.0, False
    leaf, action, kept = -1, 0, 0
    while not done:
        now = agent.leaf_of(obs)
        if not held or now != leaf or kept >= cap:
            leaf, action, kept = now, agent.predict(obs), 0
        obs, reward, terminated, truncated, _ = env.step(action)
        kept += 1
        total += float(reward)
        done = terminated or truncated
    return total


def main(task: str, seed: int, save: str | None) -> None:
    general = preset("general")
    env = gym.make(task)
    agent = general.agent(env.observation_space, env.action_space, seed)
    start = time.process_time()
    history = agent.learn(env, 1000, reset_seed=seed)
    cpu = time.process_time() - start
    if save:
        agent.save(Path(save) / f"{task}_{seed}.npz")
    seeds = [1_000_000 + 1000 * seed + i for i in range(20)]
    step = [episode(agent, env, s, held=False) for s in seeds]
    held = [episode(agent, env, s, held=True) for s in seeds]
    record = {
        "task": task,
        "seed": seed,
        "step": round(float(np.mean(step)), 1),
        "held": round(float(np.mean(held)), 1),
        "train_last100": round(float(np.mean([h.episode_return for h in history[-100:]])), 1),
        "leaves": agent.n_leaves,
        "cpu": round(cpu, 1),
    }
    with OUT.open("a") as f:
        f.write(json.dumps(record) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), sys.argv[3] if len(sys.argv) > 3 else None)
