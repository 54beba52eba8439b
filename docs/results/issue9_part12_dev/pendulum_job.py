"""Pendulum-v1 (through agent.adapt_env) with TreeConfig overrides of the general preset::

python pendulum_job.py Pendulum-v1 '{"novelty_episodes": 100}' SEED EPISODES
"""

import dataclasses
import json
import sys
import time
import warnings

import gymnasium as gym
import numpy as np

from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class

warnings.simplefilter("ignore")

task, over, seed, eps = sys.argv[1], json.loads(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
g = preset("general")
cfg = dataclasses.replace(g.config, **over)
env = adapt_env(gym.make(task))
ag = tree_agent_class(cfg)(env.observation_space, env.action_space, g.make_exploration(), seed, cfg)
t = time.process_time()
h = ag.learn(env, eps, reset_seed=seed)
c = time.process_time() - t
gr = []
for i in range(20):
    o, _ = env.reset(seed=10**6 + 1000 * seed + i)
    R = 0
    d = False
    while not d:
        o, r, te, tr, _ = env.step(ag.predict(o))
        R += r
        d = te or tr
    gr.append(R)
rets = [x.episode_return for x in h]
print(
    task,
    over,
    seed,
    eps,
    f"first100 {np.mean(rets[:100]):.1f} last100 {np.mean(rets[-100:]):.1f} "
    f"greedy {np.mean(gr):.1f} leaves {ag.n_leaves} cpu {c:.0f}",
    flush=True,
)
