"""Part 34 dev probe (round 3): can the episodes' own returns, read near the state, break the
greedy choice's ties where the leaves cannot see the swing's phase?

Training is today's general preset step for step; beside it each epoch's Monte Carlo return from
its first input is kept per (leaf, action), the last 32 (``outcome_runs.outcome_class`` with
``splits=False``; nothing the agent does reads them). The trained policy is then scored on the
same 20 greedy episodes (part 30's protocol) three ways:

* ``sel``: ``predict`` as the agent stands (today's);
* ``knn_all``: in the state's leaf, every action with at least ``K`` kept returns is valued by
  the mean return of its ``K`` kept epochs whose first inputs lie nearest the state (Euclidean,
  each input scaled by the leaf's width), and the best such action is taken (``predict`` where
  fewer than two actions have ``K``);
* ``knn_tie``: the same, among ``predict``'s action and the actions whose Q-bar is within 2
  pooled standard errors of it (the model's epochs), only where ``predict``'s action has ``K``.

    python knn_probe.py TASK OUT SEED [SEED ...]
"""

from __future__ import annotations

import json
import math
import sys
import time
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np

from agent import adapt_env, preset
from agent.tree_ensemble import tree_agent_class

sys.path.insert(0, str(Path(__file__).resolve().parent))
from outcome_runs import outcome_class  # noqa: E402

K = 8


def knn_values(agent, x, leaf, actions):
    low, high, _, _ = agent.partition.split_box(leaf)
    width = np.where(high - low > 0, high - low, 1.0)
    xv = np.asarray(x)
    out = {}
    for a in actions:
        entries = agent._outcomes.get((leaf, a))
        if entries is None or len(entries) < K:
            continue
        firsts = np.array([e[0] for e in entries]) 
        gs = np.array([e[1] for e in entries])
        d = np.sqrt((((firsts - xv) / width) ** 2).sum(axis=1))
        near = np.argsort(d, kind="stable")[:K]
        out[a] = float(gs[near].mean())
    return out


def chooser(agent, mode):
    def choose(obs):
        base = agent.predict(obs)
        if mode == "sel":
            return base
        x = np.asarray(obs, dtype=np.float64).reshape(-1).tolist()
        leaf = agent.partition.leaf_of(x)
        if mode == "knn_all":
            values = knn_values(agent, x, leaf, range(agent.n_actions))
        else:
            row = agent.q[leaf]
            se = agent.model.errors(leaf, agent.q)
            tied = [
                b
                for b in range(agent.n_actions)
                if b == base
                or abs(row[base] - row[b]) <= 2.0 * math.sqrt(se[base] ** 2 + se[b] ** 2)
            ]
            values = knn_values(agent, x, leaf, tied)
            if base not in values:
                return base
        if len(values) < 2:
            return base
        return max(values, key=lambda a: (values[a], -a))

    return choose


def main(argv: list[str]) -> None:
    warnings.simplefilter("ignore")
    task, out = argv[1], Path(argv[2])
    for seed in map(int, argv[3:]):
        env = adapt_env(gym.make(task))
        general = preset("general")
        cls = outcome_class(tree_agent_class(general.config), splits=False)
        agent = cls(env.observation_space, env.action_space, general.make_exploration(), seed, general.config)
        start = time.process_time()
        agent.learn(env, 1000, reset_seed=seed)
        row = {"task": task, "seed": seed, "cpu": round(time.process_time() - start, 1)}
        for mode in ("sel", "knn_all", "knn_tie"):
            choose = chooser(agent, mode)
            returns = []
            for i in range(20):
                obs, _ = env.reset(seed=1_000_000 + 1000 * seed + i)
                total, done = 0.0, False
                while not done:
                    obs, reward, term, trunc, _ = env.step(choose(obs))
                    total += float(reward)
                    done = term or trunc
                returns.append(total)
            row[mode] = round(float(np.mean(returns)), 2)
            row[mode + "_long"] = sum(r <= -200 for r in returns)
        with out.open("a") as f:
            f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main(sys.argv)
