"""Issue 9, part 6 (development only): the general preset with ``overrides`` on one maze layout.

One JSON line per agent seed s (first reset seed s), printed to stdout: CPU seconds, the mean
steps per episode over the run (AUC), the final steps (last 100 episodes), the 50-episode moving
average at episodes 100-800, and the leaves at the end::

    PYTHONPATH=. nice -n 5 python docs/results/issue9_failgate_dev/maze_dev.py \
        paper_narrow depth4 '{"initial_depth": 4}' 0,1,2 1000 >> paper_narrow.jsonl
"""

import dataclasses
import json
import sys
import time

import gymnasium as gym
import numpy as np

import bullet_maze  # noqa
from agent import preset
from agent.tree_ensemble import tree_agent_class

maze, label, o, seeds, episodes = (
    sys.argv[1],
    sys.argv[2],
    json.loads(sys.argv[3]),
    [int(s) for s in sys.argv[4].split(",")],
    int(sys.argv[5]),
)
g = preset("general")
for seed in seeds:
    cfg = dataclasses.replace(g.config, **o)
    env = gym.make("BulletMaze-v0", maze=maze)
    a = tree_agent_class(cfg)(
        env.observation_space, env.action_space, g.make_exploration(), seed, cfg
    )
    t = time.process_time()
    h = a.learn(env, episodes, reset_seed=seed)
    steps = np.array([s.steps for s in h], float)
    ma = np.convolve(steps, np.ones(50) / 50, mode="valid")
    out = {
        "maze": maze,
        "label": label,
        "seed": seed,
        "o": o,
        "cpu": round(time.process_time() - t, 1),
        "auc": round(steps.mean(), 1),
        "final": round(steps[-100:].mean(), 1),
        "ma_at": {
            str(e): round(float(ma[e - 50]), 1)
            for e in (100, 200, 300, 500, 800)
            if e - 50 < len(ma)
        },
        "leaves": a.n_leaves,
    }
    print(json.dumps(out), flush=True)
