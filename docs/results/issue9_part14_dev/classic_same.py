"""Part 14 check: classic control reports no collisions, so the general preset with collision
splits (part 14) and without them (``general_as_of(13)``) take the same run. Trains both on one
task for 1,000 episodes (agent seed 0, reset seed 0) and prints whether the episode returns,
Q-bar and the number of leaves are identical::

    PYTHONPATH=. python docs/results/issue9_part14_dev/classic_same.py CartPole-v1

Run on 2026-12-05 at 13:10 UTC: MountainCar-v0, CartPole-v1 and Acrobot-v1 identical (1,964,
7,860 and 4,906 leaves).
"""

from __future__ import annotations

import sys

import gymnasium as gym

from agent import general_as_of, preset
from agent.tree_ensemble import tree_agent_class


def main(task: str) -> None:
    env = gym.make(task)
    runs = []
    for config in (preset("general").config, general_as_of(13)):
        agent = tree_agent_class(config)(
            env.observation_space, env.action_space, "adaptive+tabu", 0, config
        )
        history = agent.learn(env, 1000, reset_seed=0)
        runs.append(([h.episode_return for h in history], agent.q, agent.n_leaves))
    same = "identical" if runs[0] == runs[1] else "DIFFERENT"
    print(task, same, runs[0][2], runs[1][2])


if __name__ == "__main__":
    main(sys.argv[1])
