"""Trace a trained MountainCar agent's greedy episode from given start positions.

    python mc_trace.py SEED X [X ...]
"""

from __future__ import annotations

import sys

import gymnasium as gym
import numpy as np

from agent import general_as_of, preset
from agent.tree_ensemble import tree_agent_class

seed = int(sys.argv[1])
env = gym.make("MountainCar-v0")
general = preset("general")
config = general_as_of(22)
agent = tree_agent_class(config)(env.observation_space, env.action_space, general.make_exploration(), seed, config)
agent.learn(env, 1000, reset_seed=seed)
for xs in sys.argv[2:]:
    x = float(xs)
    env.reset(seed=0)
    env.unwrapped.state = np.array([x, 0.0])
    obs = np.array([x, 0.0])
    print(f"--- start {x}")
    last = None
    for t in range(200):
        a = agent.predict(obs)
        info = agent.leaf_info(agent.leaf_of(obs))
        key = (info.leaf, a)
        if key != last:
            print(t, f"x={obs[0]:.4f} v={obs[1]:.5f} a={a} leaf={info.leaf} low={np.round(info.low,4)} high={np.round(info.high,4)} q={np.round(info.q_values,1)} n={info.visits}")
            last = key
        obs, r, term, trunc, _ = env.step(a)
        if term or trunc:
            print("end", t + 1)
            break
