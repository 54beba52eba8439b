"""Issue 9, part 6 (development only): a training curve in 100-episode blocks.

The general preset with ``model_lambda`` = LAMBDA (and ``model_lambda_watkins`` when a fourth
argument ``watkins`` is given), agent seed 0; block b is reset with seed b. One line per block:
task, lambda, block, mean training return, mean epsilon, leaves::

    PYTHONPATH=. python docs/results/issue9_lambda_dev/block_curve.py Acrobot-v1 0.9 4
"""

import dataclasses
import sys

import gymnasium as gym
import numpy as np

from agent import preset
from agent.tree_ensemble import tree_agent_class

task, lam, blocks = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
general = preset("general")
config = dataclasses.replace(
    general.config, model_lambda=lam, model_lambda_watkins=len(sys.argv) > 4
)
env = gym.make(task)
agent = tree_agent_class(config)(
    env.observation_space, env.action_space, general.make_exploration(), 0, config
)
for block in range(blocks):
    history = agent.learn(env, 100, reset_seed=block)
    train = round(float(np.mean([s.episode_return for s in history])), 1)
    epsilon = round(float(np.mean([s.mean_epsilon for s in history])), 3)
    print(task[:8], lam, block, train, epsilon, agent.n_leaves, flush=True)
