"""Part 14 dev probe: is the general agent's Q-bar converged on its own model when it stops?

Trains the general preset (committed code) on one classic task and dev seed (1,000 episodes,
first reset seed = agent seed), scores 20 greedy episodes (reset seeds 10^6 + 1000 s + i, the
protocol of tests/agent/test_classic_learning.py), then runs value iteration over the leaf
model (``LeafModel.backup_all`` passes until no V-bar moves by more than 1e-9 of the measured
unit, at most ``PASSES``) and scores the same 20 episodes again. One JSON line per job::

    PYTHONPATH=. python docs/results/issue9_part14_dev/plan_greedy.py TASK SEED
"""

from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from agent import preset

sys.path.insert(0, str(Path(__file__).resolve().parent))
from local_greedy import greedy  # beside this file; k = 0 is ``predict``

OUT = Path(__file__).with_name("plan_greedy.jsonl")
PASSES = 500


def converge(agent: Any) -> tuple[int, float, int]:
    """Value-iteration passes over the model; returns (passes, last largest change, greedy
    actions that changed)."""
    before = [int(np.argmax(row)) for row in agent.q]
    tolerance = 1e-9 * agent._in_units(1.0)
    largest, passes = math.inf, 0
    while largest > tolerance and passes < PASSES:
        changes = agent.model.backup_all(agent.q)
        largest = max(changes.values(), default=0.0)
        passes += 1
    after = [int(np.argmax(row)) for row in agent.q]
    flipped = sum(a != b for a, b in zip(before, after, strict=True))
    return passes, largest / agent._in_units(1.0), flipped


def main(task: str, seed: int) -> None:
    env = gym.make(task)
    agent = preset("general").agent(env.observation_space, env.action_space, seed)
    start = time.process_time()
    agent.learn(env, 1000, reset_seed=seed)
    cpu = time.process_time() - start
    seeds = [1_000_000 + 1000 * seed + i for i in range(20)]
    trained = greedy(agent, env, seeds, 0)
    passes, largest, flipped = converge(agent)
    planned = greedy(agent, env, seeds, 0)
    record = {
        "task": task,
        "seed": seed,
        "trained": round(trained, 1),
        "planned": round(planned, 1),
        "passes": passes,
        "last_change_units": largest,
        "flipped_leaves": flipped,
        "leaves": agent.n_leaves,
        "cpu": round(cpu, 1),
    }
    with OUT.open("a") as f:
        f.write(json.dumps(record) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]))
