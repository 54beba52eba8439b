"""Train today's general preset (``general_as_of(20)``) on one layout and save it (part 22)::

    python train_agent.py LAYOUT SEED OUT.npz

600 episodes in blocks of 50 (block b's first episode reset with seed 1000 SEED + b), the
protocol of ``issue9_hold_terminals_dev/curves.py``, so the run is that driver's run (its
final, printed here, matches the dev lines). Prints the optimum, the final (last 100 episodes'
mean steps / optimum) and the leaves.
"""

from __future__ import annotations

import sys

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa: F401  (registers BulletMaze-v0)
from agent import general_as_of, preset
from agent.tree_ensemble import tree_agent_class

if __name__ == "__main__":
    layout, seed, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    env = gym.make("BulletMaze-v0", maze=layout, max_episode_steps=5000)
    config = general_as_of(20)
    agent = tree_agent_class(config)(
        env.observation_space, env.action_space, preset("general").make_exploration(), seed, config
    )
    steps: list[int] = []
    for block in range(12):
        steps += [h.steps for h in agent.learn(env, 50, reset_seed=seed * 1000 + block)]
    optimum = env.unwrapped.optimal_steps  # type: ignore[attr-defined]
    print(layout, "optimum", optimum, "final", round(float(np.mean(steps[-100:])) / optimum, 3),
          "leaves", agent.n_leaves)
    agent.save(out)
