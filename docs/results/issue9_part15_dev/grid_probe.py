"""Issue 9, part 15 (probe after the decision): an integer-coordinate gridworld, the kind of
int Box a user may bring, where neighbouring integers are neighbouring states. N x N cells,
start (0, 0), goal (N-1, N-1), -1 a step, 4 moves, at most 20 N steps; the general preset with
its table (``table``) and with ``table_cells`` = None (``none``), 300 episodes. One JSON line::

    python docs/results/issue9_part15_dev/grid_probe.py N table|none SEED
"""

import dataclasses
import json
import sys
import time

import gymnasium as gym
import numpy as np

from agent import general_as_of
from agent.tree_ensemble import tree_agent_class

MOVES = [(1, 0), (-1, 0), (0, 1), (0, -1)]


class Grid(gym.Env):
    """N x N integer cells, start (0, 0), goal (N-1, N-1), -1 a step, at most 20 N steps."""

    def __init__(self, n: int) -> None:
        self.n = n
        self.observation_space = gym.spaces.Box(0, n - 1, (2,), dtype=np.int64)
        self.action_space = gym.spaces.Discrete(4)

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self.p, self.t = [0, 0], 0
        return np.array(self.p), {}

    def step(self, a):
        dx, dy = MOVES[a]
        n = self.n
        self.p = [min(n - 1, max(0, self.p[0] + dx)), min(n - 1, max(0, self.p[1] + dy))]
        self.t += 1
        done = self.p == [n - 1, n - 1]
        return np.array(self.p), 0.0 if done else -1.0, done, self.t >= 20 * n and not done, {}


def main(n: int, cells: str, seed: int) -> None:
    table = None if cells == "none" else 16384
    config = dataclasses.replace(general_as_of(16), table_cells=table)  # the preset of the runs
    env = Grid(n)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, "adaptive+tabu", seed, config
    )
    start = time.process_time()
    steps = [h.steps for h in agent.learn(env, 300, reset_seed=seed)]
    record = {
        "n": n,
        "cells": cells,
        "seed": seed,
        "opt": 2 * (n - 1),
        "first50": float(np.mean(steps[:50])),
        "auc": float(np.mean(steps)),
        "last50": float(np.mean(steps[-50:])),
        "leaves": agent.n_leaves,
        "cpu": round(time.process_time() - start, 1),
    }
    print(json.dumps(record), flush=True)


if __name__ == "__main__":
    main(int(sys.argv[1]), sys.argv[2], int(sys.argv[3]))
