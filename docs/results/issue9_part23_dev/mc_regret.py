"""Where a trained MountainCar agent's greedy steps lose time: each decision's regret
(optimal steps-to-go of the chosen action minus the best, from ``mc_optimal``) on the greedy
episodes from 41 start positions, grouped by how many stored epochs the leaf's model holds
for the chosen action and for the best one.

    python mc_regret.py SEED [SEED ...]
    K=1 python mc_regret.py SEED ...     (the greedy choice of ``supported_greedy`` with k = 1)
"""

from __future__ import annotations

import json
import os
import sys
from collections import defaultdict

import gymnasium as gym
import numpy as np

from agent import general_as_of, preset
from agent.tree_ensemble import tree_agent_class
from mc_optimal import qstar
from supported_greedy import greedy_action

GRID = np.linspace(-0.6, -0.4, 41)
K = int(os.environ.get("K", "0"))


def bucket(n: int) -> str:
    return "0" if n == 0 else "1-3" if n <= 3 else "4-15" if n <= 15 else "16+"


for seed in map(int, sys.argv[1:]):
    env = gym.make("MountainCar-v0")
    general = preset("general")
    config = general_as_of(22)
    agent = tree_agent_class(config)(env.observation_space, env.action_space, general.make_exploration(), seed, config)
    agent.learn(env, 1000, reset_seed=seed)
    model = agent.model
    regret = defaultdict(float)
    count = defaultdict(int)
    total_steps = 0
    decisions_bad = 0
    gap_when_bad = []
    for x0 in GRID:
        env.reset(seed=0)
        env.unwrapped.state = np.array([x0, 0.0])
        obs = np.array([x0, 0.0])
        for _ in range(200):
            leaf = agent.leaf_of(obs)
            row = agent.q[leaf]
            a = greedy_action(agent, obs, K)
            q = qstar(float(obs[0]), float(obs[1]))
            best = int(np.argmin(q))
            r = q[a] - q[best]
            key = (bucket(model.count(leaf, a)), bucket(model.count(leaf, best)))
            regret[key] += r
            count[key] += 1
            if r > 2:
                decisions_bad += 1
                gap_when_bad.append(round(row[a] - row[best], 2))
            obs, _, term, trunc, _ = env.step(a)
            total_steps += 1
            if term or trunc:
                break
    out = {
        "seed": seed,
        "k": K,
        "mean_steps": total_steps / len(GRID),
        "mean_optimal": float(np.mean([min(qstar(float(x), 0.0)) for x in GRID])),
        "regret_by_counts(chosen,best)": {f"{k[0]}|{k[1]}": [round(regret[k], 1), count[k]] for k in sorted(regret)},
        "decisions_regret_gt2": decisions_bad,
        "q_gap_when_bad": sorted(gap_when_bad),
    }
    print(json.dumps(out), flush=True)
