"""Issue 9, part 6 (development only): the tile coder on one task with trace decay LAMBDA.

``agent.tile_coding.TileCodingAgent`` with its defaults but ``lam``, agent seeds SEEDS, 1,000
episodes, then 20 greedy episodes (the protocol of ``docs/results/issue9_classic_dev/dev.py``);
one JSON line per seed on stdout::

    PYTHONPATH=. python docs/results/issue9_lambda_dev/tile_dev.py Acrobot-v1 0.0 0,1,2
"""

import json
import sys
import time
from pathlib import Path

import gymnasium as gym
import numpy as np

from agent.tile_coding import TileCodingAgent

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "issue9_classic_dev"))
from dev import greedy

task, lam = sys.argv[1], float(sys.argv[2])
for seed in [int(s) for s in sys.argv[3].split(",")]:
    env = gym.make(task)
    agent = TileCodingAgent(env.observation_space, env.action_space, seed=seed, lam=lam)
    start = time.process_time()
    history = agent.learn(env, 1000, reset_seed=seed)
    cpu = time.process_time() - start
    returns = greedy(agent, env, 20, seed)
    record = {
        "task": task,
        "label": f"tile-lam{lam}",
        "seed": seed,
        "greedy": round(float(np.mean(returns)), 1),
        "train_last100": round(float(np.mean([s.episode_return for s in history[-100:]])), 1),
        "cpu": round(cpu, 1),
    }
    print(json.dumps(record), flush=True)
